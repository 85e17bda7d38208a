build-native/methods/bhem/bhem_grid.o: methods/bhem/bhem_grid.c \
 methods/bhem/bhem.h core/problem/sb_method.h core/scene/sb_scene.h \
 core/base/sb_common.h core/base/sb_params.h core/base/sb_common.h \
 core/linalg/sb_sparse.h core/problem/sb_material_state.h \
 core/scene/sb_geometry.h core/scene/sb_scene.h core/shell/sb_shell.h \
 core/shell/sb_material.h core/base/sb_context.h core/base/sb_params.h \
 core/base/sb_stats.h
methods/bhem/bhem.h:
core/problem/sb_method.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
core/base/sb_params.h:
core/base/sb_common.h:
core/linalg/sb_sparse.h:
core/problem/sb_material_state.h:
core/scene/sb_geometry.h:
core/scene/sb_scene.h:
core/shell/sb_shell.h:
core/shell/sb_material.h:
core/base/sb_context.h:
core/base/sb_params.h:
core/base/sb_stats.h:
