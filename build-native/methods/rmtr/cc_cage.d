build-native/methods/rmtr/cc_cage.o: methods/rmtr/cc_cage.c \
 methods/rmtr/cc.h core/base/sb_common.h core/scene/sb_scene.h
methods/rmtr/cc.h:
core/base/sb_common.h:
core/scene/sb_scene.h:
