# shellbench — build, test, run, bench, report.
# `make run`  : installs missing Debian packages, builds, runs the default benchmark.
# `make test` : installs missing Debian packages, builds, runs every test.

CC      ?= cc
CXX     ?= c++
# `make NATIVE=1`: -O3 -march=native (with FMA contraction) in its own build
# directory, recorded in every record's build_id as "+native"; the default
# build is the portable x86-64 baseline whose round-off is the same on every
# machine (docs/performance.md, docs/reproducibility.md)
ifeq ($(NATIVE),1)
BUILD   ?= build-native
OPT     ?= -O3 -march=native -ffp-contract=fast
else
BUILD   ?= build
OPT     ?= -O2
endif
SAN     ?=
# element assembly on run.threads threads (OpenMP); `make OPENMP=` builds without
OPENMP  ?= -fopenmp
PKGS    := hdf5-serial jansson gsl
PKGCF    = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKGLIBS  = $(shell pkg-config --libs $(PKGS) 2>/dev/null)
CFLAGS  ?= $(OPT) -g
# core/ is the architecture, one folder per part (docs/architecture.md):
# base -> scene -> mesh -> problem (method + run) -> linalg -> solvers -> record -> report, render, study, regress, cli; contact
CORE_DIRS := base scene mesh problem linalg shell solvers record report render study regress cli contact site
CORE_INC  := $(CORE_DIRS:%=-Icore/%)
CFLAGS  += -std=c11 -Wall -Wextra -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE \
           $(CORE_INC) -I/usr/include/suitesparse $(PKGCF) $(SAN) $(OPENMP) -MMD -MP
CXXFLAGS ?= $(OPT) -g
CXXFLAGS += -std=c++14 -Wall -Wextra $(CORE_INC) $(SAN) -MMD -MP
LDLIBS   = $(PKGLIBS) -lcholmod -lsuitesparseconfig -llapack -lblas -losdCPU -lstdc++ -lz -lm
LDFLAGS += $(SAN) $(OPENMP)

DEPS_STAMP := $(BUILD)/.deps-ok

# MPI sweeps (`mpirun -n N shellbench sweep --study FILE`, docs/regression.md):
# when OpenMPI's mpicc is found (scripts/ensure_deps.sh installs it) a second
# binary, $(BUILD)/shellbench-mpi, is built with core/study/sb_sweep_mpi.c
# compiled with MPI; build/shellbench and the tests never call MPI for
# sweeps (no MPI in ordinary runs, forked runs or sanitizer builds) and hand a
# sweep started by an MPI launcher over to shellbench-mpi.  `make MPI=0`: no MPI.
# (With hypre, below, they link libmpi, which only a pcg-amg run initializes.)
MPICC ?= $(shell command -v mpicc 2>/dev/null)
ifneq ($(MPI),0)
ifneq ($(MPICC),)
MPI_CFLAGS := $(shell $(MPICC) --showme:compile 2>/dev/null)
MPI_LIBS   := $(shell $(MPICC) --showme:link 2>/dev/null)
HAVE_MPI   := 1
endif
endif

# hypre's BoomerAMG for solver.linear=pcg-amg (core/linalg/sb_precond_amg.c,
# docs/solvers.md): when Debian's libhypre-dev and OpenMPI are found.
# Debian's hypre is built against OpenMPI (no sequential variant), so linking
# it links libmpi; MPI is initialized only by the first pcg-amg set-up of a
# process, so other runs never start it.  `make HYPRE=0` (and the sanitizer
# builds) leave hypre out: pcg-amg is then refused with a sentence.
HYPRE_INC ?= /usr/include/hypre
ifeq ($(SAN),)
ifneq ($(HYPRE),0)
ifeq ($(HAVE_MPI),1)
ifneq ($(wildcard $(HYPRE_INC)/HYPRE_parcsr_ls.h),)
HAVE_HYPRE := 1
endif
endif
endif
endif
ifeq ($(HAVE_HYPRE),1)
$(BUILD)/core/linalg/sb_precond_amg.o: CFLAGS += -DSB_HAVE_HYPRE -I$(HYPRE_INC) $(MPI_CFLAGS)
LDLIBS += -lHYPRE $(MPI_LIBS)
endif

LIB_C   := $(sort $(wildcard $(CORE_DIRS:%=core/%/*.c) methods/*/*.c tests/fixture/*.c))
LIB_C   := $(filter-out core/cli/main.c,$(LIB_C))
LIB_CXX := $(sort $(wildcard methods/*/*.cpp))
LIB_OBJ := $(LIB_C:%.c=$(BUILD)/%.o) $(LIB_CXX:%.cpp=$(BUILD)/%.o)
# The fast kernel's element pass, products and denim section law
# (core/shell/sb_elem_point.c, sb_elem_tile.c, sb_section_denim.c) are compiled again for AVX2 and AVX-512, without fused
# multiply-add, and chosen at run time: the same bits as the SSE2 baseline,
# faster where the CPU has the wider vectors (docs/performance.md).  Not in
# `make NATIVE=1`, which compiles everything for the build machine already.
ifneq ($(NATIVE),1)
VEC_SRC   := sb_elem_tile sb_section_denim sb_elem_point
VEC_WIDTH := avx2 avx512
VEC_FLAGS_avx2   := -mavx2 -mno-fma
VEC_FLAGS_avx512 := -mavx512f -mno-fma
VEC_OBJ := $(foreach s,$(VEC_SRC),$(VEC_WIDTH:%=$(BUILD)/core/shell/$(s).%.o))
LIB_OBJ += $(VEC_OBJ)
$(BUILD)/core/shell/sb_shell_isa.o: CFLAGS += -DSB_VEC_VARIANTS
define VEC_RULE
$(BUILD)/core/shell/$(1).$(2).o: core/shell/$(1).c | $(DEPS_STAMP)
	@mkdir -p $$(dir $$@)
	$$(CC) $$(CFLAGS) $$(VEC_FLAGS_$(2)) -ffp-contract=off -DSB_VEC_SUFFIX=$(2) -c $$< -o $$@
endef
$(foreach s,$(VEC_SRC),$(foreach v,$(VEC_WIDTH),$(eval $(call VEC_RULE,$(s),$(v)))))
endif
LIB     := $(BUILD)/libshellbench.a
BIN     := $(BUILD)/shellbench

TEST_SRC := $(sort $(wildcard tests/test_*.c))
# every other tests/*.c is a helper linked into each test binary
TEST_HELP := $(filter-out $(TEST_SRC),$(sort $(wildcard tests/*.c)))
TEST_HELP_OBJ := $(TEST_HELP:%.c=$(BUILD)/%.o)
TEST_BIN := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
TEST_OK  := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%.result)
BENCH_SRC := $(sort $(wildcard bench/bench_*.c))
BENCH_BIN := $(BENCH_SRC:bench/%.c=$(BUILD)/bench/%)

.PHONY: all deps test run bench bench-build report check-asan check-paraview clean fuzz fuzz-build fuzz-short nightly site check-site
.DEFAULT_GOAL := all

all: $(BIN)

deps: $(DEPS_STAMP)
$(DEPS_STAMP): scripts/ensure_deps.sh
	@bash scripts/ensure_deps.sh
	@mkdir -p $(BUILD) && touch $@

# every object waits for the dependency check (order-only)
$(BUILD)/%.o: %.c | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@
$(BUILD)/%.o: %.cpp | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS) -c $< -o $@

# build id (git describe) for the records; the header changes only when the id does
BUILD_ID := $(shell git describe --always --dirty 2>/dev/null || echo unknown)$(if $(filter 1,$(NATIVE)),+native(-O3 -march=native))
$(BUILD)/build_id.h: FORCE | $(DEPS_STAMP)
	@mkdir -p $(BUILD)
	@echo '#define SB_BUILD_ID "$(BUILD_ID)"' > $@.new
	@cmp -s $@.new $@ || mv $@.new $@; rm -f $@.new
$(BUILD)/core/base/sb_sysinfo.o: $(BUILD)/build_id.h
$(BUILD)/core/base/sb_sysinfo.o: CFLAGS += -include $(BUILD)/build_id.h
.PHONY: FORCE
FORCE:

# the site's own scripts and stylesheet, embedded in the binary (docs/site.md)
SITE_ASSETS := $(wildcard core/site/assets/*)
$(BUILD)/gen/sb_site_assets.h: $(SITE_ASSETS) scripts/embed_assets.sh | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	@bash scripts/embed_assets.sh core/site/assets > $@.tmp && mv $@.tmp $@
$(BUILD)/core/site/sb_site_assets.o: $(BUILD)/gen/sb_site_assets.h
$(BUILD)/core/site/sb_site_assets.o: CFLAGS += -I$(BUILD)/gen

$(LIB): $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BIN): $(BUILD)/core/cli/main.o $(LIB)
	$(CC) $(LDFLAGS) -o $@ $^ $(LDLIBS)

ifeq ($(HAVE_MPI),1)
MPI_BIN := $(BUILD)/shellbench-mpi
$(BUILD)/core/study/sb_sweep_mpi.mpi.o: core/study/sb_sweep_mpi.c | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -DSB_HAVE_MPI $(MPI_CFLAGS) -c $< -o $@
# the MPI object comes before the archive, whose own sb_sweep_mpi.o is then not linked
$(MPI_BIN): $(BUILD)/core/cli/main.o $(BUILD)/core/study/sb_sweep_mpi.mpi.o $(LIB)
	$(CC) $(LDFLAGS) -o $@ $^ $(LDLIBS) $(MPI_LIBS)
all: $(MPI_BIN)
endif

$(TEST_HELP_OBJ): $(BUILD)/tests/%.o: tests/%.c | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Itests -c $< -o $@
$(BUILD)/tests/%: tests/%.c $(TEST_HELP_OBJ) $(LIB) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Itests -o $@ $< $(TEST_HELP_OBJ) $(LIB) $(LDFLAGS) $(LDLIBS)

$(BUILD)/bench/%: bench/%.c $(LIB) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -o $@ $< $(LIB) $(LDFLAGS) $(LDLIBS)

# The BLAS kernel set: OpenBLAS's generic x86-64 kernels (Prescott) by
# default, so that every x86-64 machine computes the same round-off and
# iteration counts on nonconvex scenes reproduce (docs/reproducibility.md);
# `make bench SB_BLAS_CORE=Haswell` trades that for faster dense factorizations.
SB_BLAS_CORE ?= Prescott
BLAS_ENV = OPENBLAS_NUM_THREADS=1 OPENBLAS_CORETYPE=$(SB_BLAS_CORE)

# HDF5's own leak on malformed files is suppressed (tests/lsan.supp)
LSAN_ENV = LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0

# Each test binary writes its own result file (and its wall seconds, for the
# summary's list of the slowest); the summary sums them.
$(BUILD)/tests/%.result: $(BUILD)/tests/% $(BIN) $(MPI_BIN)
	@t0=$$(date +%s.%N); SB_BIN=$(abspath $(BIN)) SB_ROOT=$(CURDIR) $(BLAS_ENV) $(LSAN_ENV) \
	  $(abspath $<) > $@.log 2>&1; echo $$? > $@.rc; tail -n 1 $@.log > $@; \
	  echo "$$t0 $$(date +%s.%N)" | awk '{printf "%.1f\n", $$2 - $$1}' > $@.seconds; \
	  if [ "$$(cat $@.rc)" != 0 ]; then echo "--- $< failed:"; grep -E 'FAIL|not ok|rror|Sanitizer' $@.log | head -n 30; fi

# `make test` builds and runs the independent test binaries TEST_JOBS at a
# time (default: the machine's cores), the slowest first so that the last
# ones do not run alone; no test depends on how fast it runs
# (docs/benchmarks.md "Tests").
TEST_JOBS ?= $(shell nproc 2>/dev/null || echo 2)
TEST_SLOW := test_contact_self test_rmtr test_sweep_mpi test_regress test_cli_records test_assembly
TEST_ORDER := $(filter $(TEST_SLOW:%=$(BUILD)/tests/%.result),$(TEST_OK)) \
              $(filter-out $(TEST_SLOW:%=$(BUILD)/tests/%.result),$(TEST_OK))
test:
	@$(MAKE) --no-print-directory -j$(TEST_JOBS) $(BIN) $(MPI_BIN) $(TEST_BIN)
	@rm -f $(BUILD)/tests/*.result $(BUILD)/tests/*.result.seconds
	@$(MAKE) --no-print-directory -j$(TEST_JOBS) -k $(TEST_ORDER) || true
	@bash scripts/test_summary.sh $(BUILD)/tests

run: $(BIN)
	$(BLAS_ENV) bash bench/default.sh $(BIN)

# Nightly performance regression (docs/regression.md): the suite
# bench/nightly/nightly.json against bench/nightly/baseline.json; exit 0 no
# regression, 1 regression, 2 input error.  NIGHTLY_ARGS=--update-baseline
# writes a new baseline.
nightly: $(BIN)
	@$(BLAS_ENV) $(BIN) regress $(NIGHTLY_ARGS); rc=$$?; \
	  echo "shellbench regress: exit $$rc (0 no regression, 1 regression, 2 input error; make itself exits 2 on any failure)"; \
	  $(BIN) site --history results/nightly/history.csv --baseline bench/nightly/baseline.json \
	    --report results/nightly/report.md --out results/nightly/site || echo "the nightly site was not written (above)"; \
	  exit $$rc

# The static HTML site (docs/site.md): `make site` from the committed studies'
# records, reports and nightly history into results/site (not committed);
# `make check-site` opens a small site and the committed one in headless
# Chromium (scripts/check_site.sh: console errors, failed loads, plots and
# their series, sorting, filtering, escaping; screenshots; load times).
site: $(BIN)
	$(BIN) site --out results/site

check-site: $(BIN)
	@bash scripts/check_site.sh $(BIN) $(BUILD)/check-site

bench: $(BIN) $(BENCH_BIN)
	$(BLAS_ENV) bash bench/run_all.sh $(BUILD)

# the bench programs built, nothing run (`make bench` runs them and rewrites results/)
bench-build: $(BIN) $(BENCH_BIN)

check-asan:
	$(MAKE) --no-print-directory BUILD=build-asan OPT=-O1 \
	  SAN="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" test

# Fuzzing (docs/cli.md "Fuzzing"): libFuzzer harnesses of the scene parser and
# the record readers, built with clang, ASan and UBSan in build-fuzz/; clang is
# installed by `ensure_deps.sh fuzz` here only (`make test` never needs it).
# `make fuzz` builds them and their seed corpora; `make fuzz-short` runs each
# for FUZZ_SECONDS (CI), failing on any crash, sanitizer report or abort.
FUZZ_BUILD   := build-fuzz
FUZZ_SAN     := -fsanitize=address,undefined,fuzzer-no-link -fno-sanitize=vptr -fno-omit-frame-pointer \
                -fno-sanitize-recover=undefined
FUZZ_SECONDS ?= 60

fuzz: $(BIN)
	@bash scripts/ensure_deps.sh fuzz
	@$(MAKE) --no-print-directory BUILD=$(FUZZ_BUILD) CC=clang CXX=clang++ OPT=-O1 SAN="$(FUZZ_SAN)" fuzz-build
	@bash scripts/fuzz_seeds.sh $(BIN) $(FUZZ_BUILD)/seeds
	@echo "fuzz targets: $(FUZZ_BUILD)/fuzz/fuzz_scene, $(FUZZ_BUILD)/fuzz/fuzz_record (make fuzz-short runs each $(FUZZ_SECONDS) s)"

fuzz-build: $(BUILD)/fuzz/fuzz_scene $(BUILD)/fuzz/fuzz_record

$(BUILD)/fuzz/fuzz_%: fuzz/fuzz_%.c $(LIB) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -fsanitize=fuzzer -o $@ $< $(LIB) $(LDFLAGS) $(LDLIBS)

fuzz-short: fuzz
	@$(BLAS_ENV) $(LSAN_ENV) bash scripts/fuzz_run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

# ParaView opens every method's XDMF sidecars (installs ParaView if missing;
# not part of `make test`): scripts/check_paraview.sh
check-paraview: $(BIN)
	$(BLAS_ENV) bash scripts/check_paraview.sh $(BIN) $(BUILD)/paraview

clean:
	rm -rf build build-asan build-fuzz

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
