# tools/box2d.mk -- validation against Box2D 2.4.1 and timing (issue 5).
# Included by the Makefile; uses its BUILD, LIB, TOOL_OBJ, CC, CPPFLAGS and
# TOOL_CFLAGS. Including it never needs Box2D: pkg-config is only asked
# when build/carom-box2d is built, after tools/ensure-deps.sh has had its
# chance to install libbox2d-dev and g++.
#
#   make box2d         build/carom-box2d and build/bench_step
#   make validate      sh tools/validate.sh: docs/validation.md and
#                      docs/validation-bounce.png; fails if a check is out
#                      of tolerance (about 30 s)
#   make bench-box2d   sh tools/bench-box2d.sh: docs/benchmarks.md (~2 min)

# Wherever this file is included, it does not change the default goal.
box2d_default_goal := $(.DEFAULT_GOAL)

BOX2D_BIN  := $(BUILD)/carom-box2d
BENCH_STEP := $(BUILD)/bench_step
# Deferred (=): expanded only when the recipe below runs.
BOX2D_CFLAGS = $(shell pkg-config --cflags box2d 2>/dev/null)
BOX2D_LIBS   = $(shell pkg-config --libs box2d 2>/dev/null)

.PHONY: box2d box2d-deps validate bench-box2d

box2d: $(BOX2D_BIN) $(BENCH_STEP)

box2d-deps:
	@sh tools/ensure-deps.sh box2d

$(BOX2D_BIN): tools/carom_box2d.cpp tools/scene.h $(wildcard include/*.h) $(TOOL_OBJ) $(LIB) | box2d-deps $(BUILD)/tools
	@pkg-config --exists box2d || { echo "Box2D not found (pkg-config box2d): apt-get install libbox2d-dev g++ pkg-config" >&2; exit 1; }
	$(CXX) -std=c++17 -O2 -Wall -Wextra $(CPPFLAGS) -Itools $(BOX2D_CFLAGS) \
	    tools/carom_box2d.cpp $(TOOL_OBJ) $(LIB) -o $@ $(BOX2D_LIBS) -lm

# The carom side of the timing: loads a scene, times carom_world_step only.
$(BENCH_STEP): tools/bench_step.c tools/scene.h $(wildcard include/*.h) $(TOOL_OBJ) $(LIB) | $(BUILD)/tools
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) tools/bench_step.c $(TOOL_OBJ) $(LIB) -o $@ -lm

validate: $(BUILD)/carom $(BOX2D_BIN)
	@sh tools/ensure-deps.sh plot
	sh tools/validate.sh --carom $(BUILD)/carom --box2d $(BOX2D_BIN)

bench-box2d: $(BOX2D_BIN) $(BENCH_STEP)
	sh tools/bench-box2d.sh --bench $(BENCH_STEP) --box2d $(BOX2D_BIN)

.DEFAULT_GOAL := $(box2d_default_goal)
