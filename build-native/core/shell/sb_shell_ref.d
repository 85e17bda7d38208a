build-native/core/shell/sb_shell_ref.o: core/shell/sb_shell_ref.c \
 core/shell/sb_shell.h core/shell/sb_material.h core/scene/sb_scene.h \
 core/base/sb_common.h
core/shell/sb_shell.h:
core/shell/sb_material.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
