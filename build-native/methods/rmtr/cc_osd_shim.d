build-native/methods/rmtr/cc_osd_shim.o: methods/rmtr/cc_osd_shim.cpp \
 methods/rmtr/cc_osd_shim.h
methods/rmtr/cc_osd_shim.h:
