build-native/core/base/sb_gsl.o: core/base/sb_gsl.c core/base/sb_gsl.h \
 core/base/sb_context.h core/base/sb_params.h core/base/sb_common.h \
 core/base/sb_stats.h
core/base/sb_gsl.h:
core/base/sb_context.h:
core/base/sb_params.h:
core/base/sb_common.h:
core/base/sb_stats.h:
