build-native/methods/rmtr/cc_quad.o: methods/rmtr/cc_quad.c \
 methods/rmtr/cc_method.h methods/rmtr/cc.h core/base/sb_common.h \
 core/problem/sb_method.h core/scene/sb_scene.h core/base/sb_params.h \
 core/base/sb_common.h core/linalg/sb_sparse.h \
 core/problem/sb_material_state.h core/scene/sb_geometry.h \
 core/scene/sb_scene.h core/shell/sb_shell.h core/shell/sb_material.h
methods/rmtr/cc_method.h:
methods/rmtr/cc.h:
core/base/sb_common.h:
core/problem/sb_method.h:
core/scene/sb_scene.h:
core/base/sb_params.h:
core/base/sb_common.h:
core/linalg/sb_sparse.h:
core/problem/sb_material_state.h:
core/scene/sb_geometry.h:
core/scene/sb_scene.h:
core/shell/sb_shell.h:
core/shell/sb_material.h:
