build-native/methods/rmtr/cc_reverse.o: methods/rmtr/cc_reverse.c \
 methods/rmtr/cc.h core/base/sb_common.h
methods/rmtr/cc.h:
core/base/sb_common.h:
