build-native/methods/rmtr/cc_subdiv.o: methods/rmtr/cc_subdiv.c \
 methods/rmtr/cc.h core/base/sb_common.h
methods/rmtr/cc.h:
core/base/sb_common.h:
