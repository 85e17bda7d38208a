build-native/core/scene/sb_scene_probes.o: core/scene/sb_scene_probes.c \
 core/scene/sb_scene_json.h core/scene/sb_scene.h core/base/sb_common.h
core/scene/sb_scene_json.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
