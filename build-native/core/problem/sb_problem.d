build-native/core/problem/sb_problem.o: core/problem/sb_problem.c \
 core/problem/sb_problem.h core/problem/sb_method.h core/scene/sb_scene.h \
 core/base/sb_common.h core/base/sb_params.h core/base/sb_common.h \
 core/linalg/sb_sparse.h core/problem/sb_material_state.h \
 core/linalg/sb_linsolve.h core/linalg/sb_sparse.h core/base/sb_stats.h \
 core/base/sb_context.h core/base/sb_params.h core/base/sb_stats.h \
 core/linalg/sb_galerkin.h
core/problem/sb_problem.h:
core/problem/sb_method.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
core/base/sb_params.h:
core/base/sb_common.h:
core/linalg/sb_sparse.h:
core/problem/sb_material_state.h:
core/linalg/sb_linsolve.h:
core/linalg/sb_sparse.h:
core/base/sb_stats.h:
core/base/sb_context.h:
core/base/sb_params.h:
core/base/sb_stats.h:
core/linalg/sb_galerkin.h:
