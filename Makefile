# carom -- build, test and run. `make help` lists the targets.

CC      ?= cc
BUILD   ?= build
OPT     ?= -O2 -g
WARN    := -std=c99 -pedantic -Wall -Wextra -Werror -Wdouble-promotion \
           -ffp-contract=off
# Extra -D switches for the library (see include/carom_config.h), e.g.
#   make CAROM_FLAGS='-DCAROM_ENABLE_POLYGONS=0'
CAROM_FLAGS ?=
CPPFLAGS := -Iinclude $(CAROM_FLAGS)
CFLAGS  := $(WARN) $(OPT)
# Tools may use POSIX and libm; the core may not.
TOOL_CFLAGS := $(CFLAGS) -D_POSIX_C_SOURCE=200809L -Itools

# The compiler and flags a build directory's objects were made with: the
# stamp changes only when they do, and every object depends on it, so
# `make CAROM_FLAGS=...` after a plain `make` rebuilds instead of keeping
# a library of other switches (a program and a library of different
# switches disagree on the layout of carom's structs).
FLAGS_STAMP := $(BUILD)/flags.stamp
FLAGS_NOW := $(CC) $(CPPFLAGS) $(CFLAGS)

LIB_SRC := $(wildcard src/*.c)
LIB_OBJ := $(LIB_SRC:src/%.c=$(BUILD)/obj/%.o)
LIB     := $(BUILD)/libcarom.a
# The same library with the op counters compiled in (CAROM_ENABLE_PROFILE):
# build/carom links it so that `carom profile` can count; results are the
# same bits, counting never changes the arithmetic.
PROF_FLAGS := -DCAROM_ENABLE_PROFILE=1
PROF_OBJ := $(LIB_SRC:src/%.c=$(BUILD)/profile/obj/%.o)
PROF_LIB := $(BUILD)/profile/libcarom.a
CLI     := $(BUILD)/carom
# The same tool linked with the plain library (no counters: `profile`
# says so). The stress suite and bench-box2d time it: the library a
# program links, as Box2D's harness times its release build.
CLI_PLAIN := $(BUILD)/carom-plain
TOOL_OBJ := $(BUILD)/tools/scene.o
# The option parser of build/carom and build/carom-box2d.
CLI_OPT_OBJ := $(BUILD)/tools/cli_options.o
TEST_SRC := $(wildcard tests/test_*.c)
TEST_BIN := $(BUILD)/carom_tests

CHECK_CFLAGS = $(shell pkg-config --cflags check 2>/dev/null)
CHECK_LIBS   = $(shell pkg-config --libs check 2>/dev/null)

SCENE ?= tools/scenes/default.scene

# Plain `make` builds `all`, whatever the fragments included below define
# first (help-check fails if this changes).
.DEFAULT_GOAL := all

# The Box2D 2.4.1 harness (tools/box2d.mk): `make` builds build/carom-box2d
# when Box2D is installed.
include tools/box2d.mk
# make validate, make validate-check (tools/validation/validation.mk).
include tools/validation/validation.mk
# Speed and memory at scale, carom's methods against Box2D 2.4.1 and v3
# (tools/bench/bench.mk): make bench, bench-quick, bench-build. Speed and
# memory targets live there, not in unit tests.
include tools/bench/bench.mk
# make box2d-v3 B2V3_DIR=...: the Box2D v3 harness build/carom-box2d-v3
# (tools/box2d_v3/box2d_v3.mk; Box2D v3 built outside the project).
include tools/box2d_v3/box2d_v3.mk
# Error against run time (tools/accuracy/accuracy.mk): make accuracy,
# make accuracy-check.
include tools/accuracy/accuracy.mk
# The stress suite (tools/stress/stress.mk): make stress, make stress-check.
include tools/stress/stress.mk
# `carom render`'s drawing code (tools/render/render.mk), linked into build/carom.
include tools/render/render.mk
# make shared, install, uninstall, install-test, check-cxx (mk/install.mk).
include mk/install.mk
# The scene suite on emulated Cortex-M (tools/embedded/embedded.mk):
# check-embedded, check-embedded-negative, embedded-insn, embedded-size.
include tools/embedded/embedded.mk
# make lean SCENE=FILE, make lean-check: the smallest build for a scene.
include mk/lean.mk
# make fuzz, fuzz-check, fuzz-regress, fuzz-build, fuzz-clean: libFuzzer (tests/fuzz/).
include tests/fuzz/fuzz.mk
# make docs-check: every path, file and make target the docs name exists.
include mk/docs.mk
# make coverage, coverage-check, sanitize, memcheck (mk/quality.mk).
include mk/quality.mk
HAVE_BOX2D := $(shell pkg-config --exists box2d 2>/dev/null && echo yes)

.PHONY: check-cross all lib cli check unit unit-nogrid check-soft-deep cli-test readme-test check-symbols check-switches run clean help deps
.PHONY: help-check examples-check header-example-check

EXAMPLES := $(patsubst examples/%.c,$(BUILD)/examples/%,$(wildcard examples/*.c))

all: $(LIB) $(CLI) $(EXAMPLES) $(if $(HAVE_BOX2D),$(BOX2D_BIN))

# The example programs (examples/): plain C against the public header and
# the library, as a program of yours would be.
$(BUILD)/examples/%: examples/%.c include/carom.h include/carom_config.h $(LIB) | $(BUILD)/examples
	$(CC) $(CPPFLAGS) $(CFLAGS) $< $(LIB) -o $@ $(LDFLAGS) -lm

$(BUILD)/examples:
	mkdir -p $@

# Each example runs headless and checks its own outcome (exit status).
examples-check: $(EXAMPLES)
	@for e in $(EXAMPLES); do echo "$$e"; $$e || exit 1; done

lib: $(LIB)
cli: $(CLI)

$(BUILD)/obj/%.o: src/%.c $(wildcard src/*.h include/*.h) $(FLAGS_STAMP) | $(BUILD)/obj
	$(CC) $(CPPFLAGS) $(CFLAGS) -c $< -o $@

$(LIB): $(LIB_OBJ)
	rm -f $@
	ar rcs $@ $^

$(BUILD)/profile/obj/%.o: src/%.c $(wildcard src/*.h include/*.h) $(FLAGS_STAMP) | $(BUILD)/profile/obj
	$(CC) $(CPPFLAGS) $(PROF_FLAGS) $(CFLAGS) -c $< -o $@

$(PROF_LIB): $(PROF_OBJ)
	rm -f $@
	ar rcs $@ $^

$(BUILD)/tools/%.o: tools/%.c $(wildcard tools/*.h include/*.h) $(FLAGS_STAMP) | $(BUILD)/tools
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -c $< -o $@

$(BUILD)/tools/carom_cli.o: tools/carom_cli.c $(wildcard tools/*.h include/*.h) $(FLAGS_STAMP) | $(BUILD)/tools
	$(CC) $(CPPFLAGS) $(PROF_FLAGS) $(TOOL_CFLAGS) -c $< -o $@

$(CLI): $(BUILD)/tools/carom_cli.o $(CLI_OPT_OBJ) $(TOOL_OBJ) $(PROF_LIB)
	$(CC) $(OPT) $(LDFLAGS) $^ -o $@ -lm

$(BUILD)/tools/carom_cli_plain.o: tools/carom_cli.c $(wildcard tools/*.h include/*.h) $(FLAGS_STAMP) | $(BUILD)/tools
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -c $< -o $@

$(CLI_PLAIN): $(BUILD)/tools/carom_cli_plain.o $(CLI_OPT_OBJ) $(TOOL_OBJ) $(LIB)
	$(CC) $(OPT) $(LDFLAGS) $^ -o $@ -lm

$(BUILD)/obj $(BUILD)/tools $(BUILD)/tests $(BUILD)/profile/obj:
	mkdir -p $@

$(FLAGS_STAMP): FORCE
	@mkdir -p $(dir $@)
	@printf '%s\n' '$(FLAGS_NOW)' | cmp -s - $@ || printf '%s\n' '$(FLAGS_NOW)' > $@

FORCE:

# ---- tests -------------------------------------------------------------------

deps:
	@sh tools/ensure-deps.sh check

$(TEST_BIN): $(TEST_SRC) tests/test_util.h $(TOOL_OBJ) $(LIB) | $(BUILD)/tests
	$(CC) $(CPPFLAGS) -Isrc $(TOOL_CFLAGS) -Wno-double-promotion $(CHECK_CFLAGS) \
	    $(TEST_SRC) $(TOOL_OBJ) $(LIB) -o $@ $(LDFLAGS) $(CHECK_LIBS) -lm

# The whole suite again against the profiling build: same results, plus the
# exact operation counts of tests/test_profile.c.
$(TEST_BIN)_profile: $(TEST_SRC) tests/test_util.h $(TOOL_OBJ) $(PROF_LIB) | $(BUILD)/tests
	$(CC) $(CPPFLAGS) $(PROF_FLAGS) -Isrc $(TOOL_CFLAGS) -Wno-double-promotion $(CHECK_CFLAGS) \
	    $(TEST_SRC) $(TOOL_OBJ) $(PROF_LIB) -o $@ $(LDFLAGS) $(CHECK_LIBS) -lm

unit: deps
	@$(MAKE) --no-print-directory $(TEST_BIN) $(TEST_BIN)_profile
	CK_DEFAULT_TIMEOUT=120 $(TEST_BIN)
	CK_DEFAULT_TIMEOUT=120 $(TEST_BIN)_profile

# The whole unit suite against a library without the broadphase grid
# (CAROM_ENABLE_GRID=0, what `carom lean` picks for small worlds): every
# result, pinned hashes included, must be the grid build's.
unit-nogrid: deps
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/nogrid CAROM_FLAGS='$(CAROM_FLAGS) -DCAROM_ENABLE_GRID=0' $(BUILD)/nogrid/carom_tests
	CK_DEFAULT_TIMEOUT=120 $(BUILD)/nogrid/carom_tests

# The whole unit suite against a library built with the soft push of deep
# overlaps between unlike bodies (CAROM_SOFT_DEEP_CONTACTS=1, off by
# default), then the mixed-density pile it settles.
check-soft-deep: deps
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/soft CAROM_FLAGS='$(CAROM_FLAGS) -DCAROM_SOFT_DEEP_CONTACTS=1' $(BUILD)/soft/carom_tests $(BUILD)/soft/carom $(BUILD)/soft/stress_check
	CK_DEFAULT_TIMEOUT=120 $(BUILD)/soft/carom_tests
	sh tools/check-soft-deep.sh $(BUILD)/soft

cli-test: $(CLI) $(CLI_PLAIN)
	sh tests/cli_test.sh $(CLI) $(CLI_PLAIN)

# The README's example program must compile and run against the library.
readme-test: $(LIB) | $(BUILD)/tests
	awk '/^```c$$/{f=1;next} /^```$$/{f=0} f' README.md > $(BUILD)/tests/readme_example.c
	$(CC) $(CPPFLAGS) $(CFLAGS) $(BUILD)/tests/readme_example.c $(LIB) -lm -o $(BUILD)/tests/readme_example
	$(BUILD)/tests/readme_example

# The minimal program in carom.h's opening comment must compile and run
# (and print what the comment says it prints).
header-example-check: $(LIB) | $(BUILD)/tests
	sh tools/header-example.sh include/carom.h $(BUILD)/tests/header_example.c
	$(CC) $(CPPFLAGS) $(CFLAGS) $(BUILD)/tests/header_example.c $(LIB) -lm -o $(BUILD)/tests/header_example
	$(BUILD)/tests/header_example > $(BUILD)/tests/header_example.out
	grep -q "^ball at 0 0.5$$" $(BUILD)/tests/header_example.out || { cat $(BUILD)/tests/header_example.out; echo "header example: not the output its comment promises" >&2; exit 1; }

# The library must not allocate, and must call no libm function but sqrtf:
# inspect the undefined symbols of the built archive.
check-symbols: $(LIB) $(PROF_LIB)
	sh tools/check-symbols.sh $(LIB) $(PROF_LIB)

# The core builds for a Cortex-M4F (when arm-none-eabi-gcc is installed).
check-cross:
	sh tools/check-cross.sh $(BUILD)/m4f

# Every switch of carom_config.h builds, and removes (or adds) code.
check-switches:
	sh tools/check-switches.sh

check: deps
	@sh tools/ensure-deps.sh box2d plot
	@$(MAKE) --no-print-directory all
	@$(MAKE) --no-print-directory check-symbols
	@$(MAKE) --no-print-directory check-switches
	@$(MAKE) --no-print-directory check-cross
	@$(MAKE) --no-print-directory unit
	@$(MAKE) --no-print-directory unit-nogrid
	@$(MAKE) --no-print-directory check-soft-deep
	@$(MAKE) --no-print-directory readme-test
	@$(MAKE) --no-print-directory header-example-check
	@$(MAKE) --no-print-directory examples-check
	@$(MAKE) --no-print-directory validate-check
	@$(MAKE) --no-print-directory cli-test
	@$(MAKE) --no-print-directory stress-check
	@$(MAKE) --no-print-directory accuracy-check
	@$(MAKE) --no-print-directory check-embedded
	@$(MAKE) --no-print-directory lean-check
	@$(MAKE) --no-print-directory fuzz-check
	@$(MAKE) --no-print-directory install-test
	@$(MAKE) --no-print-directory check-cxx
	@$(MAKE) --no-print-directory coverage-check
	@$(MAKE) --no-print-directory sanitize
	@$(MAKE) --no-print-directory memcheck
	@$(MAKE) --no-print-directory help-check
	@$(MAKE) --no-print-directory docs-check

# ---- the main job -----------------------------------------------------------

run: $(CLI)
	@sh tools/run-default.sh $(CLI) $(SCENE)


clean:
	rm -rf $(BUILD)

# One line per target; `make help-check` fails if a .PHONY target of the
# Makefile or its fragments is missing here.
help:
	@echo "carom: make targets (variables: BUILD=$(BUILD) CC=$(CC) PREFIX=$(PREFIX) DESTDIR= SCENE= CAROM_FLAGS=)"
	@echo ""
	@echo "build"
	@echo "  make all             the default (plain make): $(LIB), $(CLI), $(BUILD)/examples/, and $(BOX2D_BIN) if Box2D is installed"
	@echo "  make lib             $(LIB) only"
	@echo "  make cli             $(CLI) only (linked with the profiling build, $(PROF_LIB))"
	@echo "  make shared          $(SHLIB) (soname $(SONAME), -fPIC objects in $(BUILD)/pic/) and its symlinks"
	@echo "  make box2d           $(BOX2D_BIN) (Box2D 2.4.1 harness; needs libbox2d-dev, g++)"
	@echo "  make embedded        the Cortex-M libraries, firmware and host suite of check-embedded; runs nothing"
	@echo "  make embedded-host   the embedded scene suite built for this machine (the reference hashes)"
	@echo "  make fuzz-build      the libFuzzer harnesses only, in $(BUILD)/fuzz/"
	@echo ""
	@echo "test"
	@echo "  make check           the whole suite: deps, all, check-symbols, check-switches, check-cross, unit, unit-nogrid, check-soft-deep, readme-test, header-example-check, examples-check, validate-check, cli-test, stress-check, accuracy-check, check-embedded, lean-check, fuzz-check (reproducible, ~30 s a harness when clang is here), install-test, check-cxx, coverage-check, sanitize, memcheck, help-check, docs-check"
	@echo "  make unit            the Check unit tests, plain and profiling builds"
	@echo "  make unit-nogrid     the unit tests against a library built with CAROM_ENABLE_GRID=0 (same results)"
	@echo "  make check-soft-deep  the unit tests against a library built with CAROM_SOFT_DEEP_CONTACTS=1, and the mixed-density pile it settles"
	@echo "  make cli-test        $(CLI)'s command-line tests (tests/cli_test.sh)"
	@echo "  make readme-test     the README's example program compiles and runs"
	@echo "  make header-example-check  the minimal program in carom.h's opening comment compiles, runs and prints what it says"
	@echo "  make examples-check  build/examples/breakout and balance run headless and check their outcome"
	@echo "  make check-symbols   the archives call no allocator and no libm function but sqrtf"
	@echo "  make check-switches  every switch of include/carom_config.h builds and removes code"
	@echo "  make check-cross     the core builds for a Cortex-M4F (skipped without arm-none-eabi-gcc)"
	@echo "  make check-embedded  the scene suite under qemu on Cortex-M4F, M3 and M0 must match the x86-64 hashes; then embedded-lean8k"
	@echo "  make check-embedded-negative  the M4F firmware with fused multiply-add must fail that comparison"
	@echo "  make validate-check  carom against Box2D within tolerance; report and figure under $(BUILD)/"
	@echo "  make stress-check    the stress checker's self-test, then the fast stress scenes (a few seconds)"
	@echo "  make accuracy-check  the fast accuracy subset (bounce and projectile at three dt) with tolerances (seconds)"
	@echo "  make fuzz            build the libFuzzer harnesses, fuzz each FUZZ_SECONDS (30), replay; needs clang"
	@echo "  make fuzz-check      reproducible fuzzing (seed FUZZ_SEED=1, a fixed number of inputs a harness, ~30 s each), then the replay; needs clang"
	@echo "  make fuzz-regress    replay the fuzz seed corpus and tests/fuzz/crashers/ (seconds)"
	@echo "  make install-test    install into a temporary DESTDIR, build and run a program with pkg-config, uninstall"
	@echo "  make check-cxx       include/carom.h compiles as C++98 and C++17 (-Wall -Wextra -Werror -pedantic)"
	@echo "  make help-check      every .PHONY target is listed by make help"
	@echo "  make docs-check      every path and file the README and docs/ name exists; every make target they name is in make help"
	@echo "  make coverage        unit and CLI tests built with --coverage: $(BUILD)/coverage/index.html and summary.json over src/ (gcovr)"
	@echo "  make coverage-check  make coverage, then fail below 95 % of lines or 85 % of branches of src/"
	@echo "  make sanitize        unit and CLI tests under AddressSanitizer and UndefinedBehaviorSanitizer (SAN_CC=gcc or clang)"
	@echo "  make memcheck        the CLI under valgrind memcheck on every example scene and six stress scenes"
	@echo ""
	@echo "run and report"
	@echo "  make run             run SCENE (default $(SCENE)): impacts, final state, operation counts"
	@echo "  make validate        carom against Box2D 2.4.1 and exact answers (466 checks): regenerates docs/validation.md (~15 s)"
	@echo "  make bench           carom's methods against Box2D 2.4.1 (and v3 with B2V3_DIR=) at 10^2..10^5 bodies: docs/benchmarks.md, docs/bench-*.png (~10 min)"
	@echo "  make bench-quick     the same at 10^2 and 10^3 bodies, report under $(BUILD)/bench/ (~1 min)"
	@echo "  make bench-build     $(BUILD)/carom-bench and $(BUILD)/carom-bench-ops only"
	@echo "  make stress          every stress scene through carom and Box2D 2.4.1 (and v3 with B2V3_DIR=): docs/stability.md (~2 min)"
	@echo "  make box2d-v3        build/carom-box2d-v3, scene files through Box2D v3 (needs B2V3_DIR=, tools/box2d_v3/BUILDING.md)"
	@echo "  make accuracy        error against run time, every method and Box2D over dt 1/15..1/3840: docs/accuracy.md and figures (a few minutes)"
	@echo "  make bench-box2d     the pyramid and pour scenes timed against Box2D 2.4.1, one run at a time: events within 2x, discrete no slower (~1 min)"
	@echo "  make stress-scenes   regenerate tools/scenes/stress (python3)"
	@echo "  make render-images   redraw docs/images/ with carom render (default scene animated; stills; needs gnuplot)"
	@echo "  make embedded-insn   instructions per run on the emulated M4F against carom profile --weights cortex-m4f"
	@echo "  make embedded-size   text, data and bss of the library per Cortex-M core"
	@echo "  make embedded-calibrate  fit the profiler's instruction model to qemu's per-phase counts (tools/embedded/cortex-m4f.cal)"
	@echo "  make embedded-lean8k  the bounce and 5-box stack scenes with their lean capacities in 8 KB of world memory on the M0"
	@echo "  make embedded-doc    regenerate docs/embedded.md (footprints, stack, memory, calibration; ~7 min)"
	@echo "  make lean            SCENE=FILE: build/lean/libcarom.a and build/lean/carom for that scene, size table, bit-identical check"
	@echo "  make lean-check      make lean on five example scenes, checked (seconds)"
	@echo ""
	@echo "install"
	@echo "  make install         headers, libcarom.a, libcarom.so.$(VERSION), carom.pc, bin/carom, docs into DESTDIR/PREFIX"
	@echo "  make uninstall       remove every file make install put there (the bin/, include/ and lib/ directories stay)"
	@echo ""
	@echo "other"
	@echo "  make deps            install the unit tests' packages with apt-get if missing (when root or sudo)"
	@echo "  make box2d-deps      the same for Box2D 2.4.1 and g++"
	@echo "  make box2d-v3-deps   check that B2V3_DIR (or B2V3_INC, B2V3_LIB) holds Box2D v3's header and library"
	@echo "  make clean           remove $(BUILD)/"
	@echo "  make fuzz-clean      remove $(BUILD)/fuzz/"
	@echo "  make help            this list"

help-check:
	@$(MAKE) --no-print-directory -s help > $(BUILD)/.help.txt 2>/dev/null || { mkdir -p $(BUILD) && $(MAKE) --no-print-directory -s help > $(BUILD)/.help.txt; }
	@missing=; \
	for t in $$($(MAKE) --no-print-directory -pRrq -f $(firstword $(MAKEFILE_LIST)) : 2>/dev/null | sed -n 's/^\.PHONY: *//p'); do \
	    grep -q -E "^ *make $$t( |$$)" $(BUILD)/.help.txt || missing="$$missing $$t"; \
	done; \
	rm -f $(BUILD)/.help.txt; \
	if [ -n "$$missing" ]; then echo "make help does not list:$$missing" >&2; exit 1; fi; \
	echo "make help lists every .PHONY target"
	@goal=$$($(MAKE) --no-print-directory -pRrq -f $(firstword $(MAKEFILE_LIST)) : 2>/dev/null | sed -n 's/^\.DEFAULT_GOAL := //p'); \
	if [ "$$goal" != all ]; then echo "plain make builds '$$goal', not 'all'" >&2; exit 1; fi; \
	echo "plain make builds all"
