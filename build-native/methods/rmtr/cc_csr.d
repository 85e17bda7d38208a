build-native/methods/rmtr/cc_csr.o: methods/rmtr/cc_csr.c \
 methods/rmtr/cc.h core/base/sb_common.h
methods/rmtr/cc.h:
core/base/sb_common.h:
