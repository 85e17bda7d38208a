build-native/core/solvers/tr.o: core/solvers/tr.c \
 core/solvers/sb_solver.h core/problem/sb_problem.h \
 core/problem/sb_method.h core/scene/sb_scene.h core/base/sb_common.h \
 core/base/sb_params.h core/base/sb_common.h core/linalg/sb_sparse.h \
 core/problem/sb_material_state.h core/linalg/sb_linsolve.h \
 core/linalg/sb_sparse.h core/base/sb_stats.h core/solvers/sb_trs.h
core/solvers/sb_solver.h:
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
core/solvers/sb_trs.h:
