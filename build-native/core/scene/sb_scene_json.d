build-native/core/scene/sb_scene_json.o: core/scene/sb_scene_json.c \
 core/scene/sb_scene_json.h core/scene/sb_scene.h core/base/sb_common.h \
 core/scene/sb_json_pos.h
core/scene/sb_scene_json.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
core/scene/sb_json_pos.h:
