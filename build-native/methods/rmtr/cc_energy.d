build-native/methods/rmtr/cc_energy.o: methods/rmtr/cc_energy.c \
 methods/rmtr/cc_method.h methods/rmtr/cc.h core/base/sb_common.h \
 core/problem/sb_method.h core/scene/sb_scene.h core/base/sb_params.h \
 core/base/sb_common.h core/linalg/sb_sparse.h \
 core/problem/sb_material_state.h core/scene/sb_geometry.h \
 core/scene/sb_scene.h core/shell/sb_shell.h core/shell/sb_material.h \
 core/linalg/sb_assemble.h
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
core/linalg/sb_assemble.h:
