build-native/core/shell/sb_stability.o: core/shell/sb_stability.c \
 core/shell/sb_shell.h core/shell/sb_material.h core/scene/sb_scene.h \
 core/base/sb_common.h core/problem/sb_material_state.h
core/shell/sb_shell.h:
core/shell/sb_material.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
core/problem/sb_material_state.h:
