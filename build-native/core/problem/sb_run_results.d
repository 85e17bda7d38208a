build-native/core/problem/sb_run_results.o: core/problem/sb_run_results.c \
 core/problem/sb_run_state.h core/base/sb_context.h core/base/sb_params.h \
 core/base/sb_common.h core/base/sb_stats.h core/problem/sb_problem.h \
 core/problem/sb_method.h core/scene/sb_scene.h core/base/sb_common.h \
 core/base/sb_params.h core/linalg/sb_sparse.h \
 core/problem/sb_material_state.h core/linalg/sb_linsolve.h \
 core/linalg/sb_sparse.h core/base/sb_stats.h core/record/sb_record.h \
 core/problem/sb_material_state.h core/problem/sb_run.h \
 core/solvers/sb_solver.h core/problem/sb_problem.h \
 core/scene/sb_geometry.h core/scene/sb_scene.h
core/problem/sb_run_state.h:
core/base/sb_context.h:
core/base/sb_params.h:
core/base/sb_common.h:
core/base/sb_stats.h:
core/problem/sb_problem.h:
core/problem/sb_method.h:
core/scene/sb_scene.h:
core/base/sb_common.h:
core/base/sb_params.h:
core/linalg/sb_sparse.h:
core/problem/sb_material_state.h:
core/linalg/sb_linsolve.h:
core/linalg/sb_sparse.h:
core/base/sb_stats.h:
core/record/sb_record.h:
core/problem/sb_material_state.h:
core/problem/sb_run.h:
core/solvers/sb_solver.h:
core/problem/sb_problem.h:
core/scene/sb_geometry.h:
core/scene/sb_scene.h:
