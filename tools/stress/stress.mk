# tools/stress/stress.mk -- the stress suite (tools/stress/, docs/stability.md).
# Meant to be included by the Makefile (after tools/box2d.mk); uses its CC,
# BUILD, CPPFLAGS, TOOL_CFLAGS, LIB, TOOL_OBJ, CLI_PLAIN and BOX2D_BIN. Standalone:
#   make -f Makefile -f tools/stress/stress.mk stress-check
#
#   make stress          every scene of tools/scenes/stress through carom
#                        (events, discrete), Box2D 2.4.1 and, with
#                        B2V3_DIR=PREFIX (Box2D v3 built outside the
#                        project, tools/box2d_v3/BUILDING.md), the Box2D v3
#                        harness build/carom-box2d-v3, built first (or any
#                        harness given as STRESS_V3=PATH);
#                        writes docs/stability.md and docs/stability-*.png;
#                        fails if a carom result fails (~10 min on 2 cores)
#   make stress-check    the checker's self-test (tools/stress/selftest.sh),
#                        then the fast subset ('# fast' scenes), no report
#                        (a few seconds)
#   make stress-scenes   regenerate tools/scenes/stress (python3)
#
# STRESS_JOBS (default 2) runs that many engine runs at once.

STRESS_CHECK := $(BUILD)/stress_check
STRESS_JOBS ?= 2
# B2V3_LIB and B2V3_BIN come from tools/box2d_v3/box2d_v3.mk when the
# Makefile includes it.
STRESS_V3_BUILD := $(if $(B2V3_LIB),$(B2V3_BIN))
STRESS_V3 ?= $(STRESS_V3_BUILD)
STRESS_BOX2D := $(if $(shell pkg-config --exists box2d 2>/dev/null && echo yes),$(BOX2D_BIN))
# carom runs as $(CLI_PLAIN): the library without its op counters, as a
# program links it (the same bits as $(CLI): tests/cli_test.sh), and timed
# so, as Box2D's harness times its release build.
STRESS_ARGS = --carom $(CLI_PLAIN) --box2d $(BOX2D_BIN) --checker $(STRESS_CHECK) \
    --jobs $(STRESS_JOBS) $(if $(STRESS_V3),--v3 $(STRESS_V3))

# The pile, pyramid and pour scenes, timed side by side with Box2D 2.4.1
# (one run at a time) against the speed targets.
BENCH_BOX2D_SCENES ?= pyramid-b20,pyramid-b40,pour-500,pyramid-b20-s0.01,pyramid-b20-s100,pour-500-s100

.PHONY: stress stress-check stress-scenes bench-box2d

# Reads scenes with tools/scene.c only (scene_load); no library internals.
$(STRESS_CHECK): tools/stress/stress_check.c tools/scene.h $(wildcard include/*.h) $(FLAGS_STAMP) $(TOOL_OBJ) $(LIB) | $(BUILD)/tools
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) tools/stress/stress_check.c $(TOOL_OBJ) $(LIB) -o $@ -lm

stress: $(CLI_PLAIN) $(STRESS_CHECK) $(STRESS_BOX2D) $(STRESS_V3_BUILD)
	@sh tools/ensure-deps.sh plot
	sh tools/stress/run.sh $(STRESS_ARGS) --report docs/stability.md

stress-check: $(CLI_PLAIN) $(STRESS_CHECK) $(STRESS_BOX2D)
	sh tools/stress/selftest.sh $(STRESS_CHECK)
	sh tools/stress/run.sh $(STRESS_ARGS) --fast

bench-box2d: $(CLI_PLAIN) $(STRESS_CHECK) $(STRESS_BOX2D)
	@test -n "$(STRESS_BOX2D)" || { echo "bench-box2d: Box2D 2.4.1 not found (apt-get install libbox2d-dev)" >&2; exit 1; }
	sh tools/stress/run.sh $(STRESS_ARGS) --jobs 1 --only $(BENCH_BOX2D_SCENES) --targets

stress-scenes:
	python3 tools/stress/gen_scenes.py
