build-native/core/scene/sb_scene_domain.o: core/scene/sb_scene_domain.c \
 core/scene/sb_geometry.h core/scene/sb_scene.h core/base/sb_common.h \
 core/scene/sb_scene_json.h
core/scene/sb_geometry.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
core/scene/sb_scene_json.h:
