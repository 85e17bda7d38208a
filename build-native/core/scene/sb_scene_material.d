build-native/core/scene/sb_scene_material.o: \
 core/scene/sb_scene_material.c core/scene/sb_scene_json.h \
 core/scene/sb_scene.h core/base/sb_common.h core/shell/sb_material.h \
 core/scene/sb_scene.h
core/scene/sb_scene_json.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
core/shell/sb_material.h:
core/scene/sb_scene.h:
