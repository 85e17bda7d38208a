build-native/methods/rmtr/cc_mesh.o: methods/rmtr/cc_mesh.c \
 methods/rmtr/cc.h core/base/sb_common.h
methods/rmtr/cc.h:
core/base/sb_common.h:
