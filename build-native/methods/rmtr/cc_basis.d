build-native/methods/rmtr/cc_basis.o: methods/rmtr/cc_basis.c \
 methods/rmtr/cc.h core/base/sb_common.h
methods/rmtr/cc.h:
core/base/sb_common.h:
