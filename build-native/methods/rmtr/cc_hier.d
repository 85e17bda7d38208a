build-native/methods/rmtr/cc_hier.o: methods/rmtr/cc_hier.c \
 methods/rmtr/cc.h core/base/sb_common.h methods/rmtr/cc_osd_shim.h
methods/rmtr/cc.h:
core/base/sb_common.h:
methods/rmtr/cc_osd_shim.h:
