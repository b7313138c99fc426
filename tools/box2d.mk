# tools/box2d.mk -- validation against Box2D 2.4.1 and timing (issue 5).
# Included by the Makefile; uses its BUILD, LIB, TOOL_OBJ, CC, CPPFLAGS and
# TOOL_CFLAGS. Including it never needs Box2D: pkg-config is only asked
# when build/carom-box2d is actually built.
#
#   make box2d         build/carom-box2d (installs libbox2d-dev, g++ if root)
#   make validate      sh tools/validate.sh: docs/validation.md, the figure;
#                      fails if an agreement case is out of tolerance
#   make bench-box2d   sh tools/bench-box2d.sh: docs/benchmarks.md

BOX2D_BIN   := $(BUILD)/carom-box2d
BENCH_STEP  := $(BUILD)/bench_step
BOX2D_CXX   ?= g++
# Deferred (=): evaluated only inside the recipe below.
BOX2D_FLAGS  = $(shell pkg-config --cflags box2d 2>/dev/null)
BOX2D_LIBS   = $(shell pkg-config --libs box2d 2>/dev/null)

.PHONY: box2d box2d-deps validate bench-box2d

box2d-deps:
	@sh tools/ensure-deps.sh box2d plot

box2d: box2d-deps
	@$(MAKE) --no-print-directory $(BOX2D_BIN) $(BENCH_STEP)

$(BOX2D_BIN): tools/carom_box2d.cpp tools/scene.h $(wildcard include/*.h) $(TOOL_OBJ) $(LIB) | $(BUILD)/tools
	@pkg-config --exists box2d || { echo "Box2D not found (pkg-config box2d): run 'sh tools/ensure-deps.sh box2d' or 'apt-get install libbox2d-dev g++ pkg-config'" >&2; exit 1; }
	$(BOX2D_CXX) -std=c++17 -O2 -Wall -Wextra $(CPPFLAGS) -Itools $(BOX2D_FLAGS) \
	    tools/carom_box2d.cpp $(TOOL_OBJ) $(LIB) -o $@ $(BOX2D_LIBS) -lm

# The carom side of the timing: loads a scene, times carom_world_step only.
$(BENCH_STEP): tools/bench_step.c tools/scene.h $(wildcard include/*.h) $(TOOL_OBJ) $(LIB) | $(BUILD)/tools
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) tools/bench_step.c $(TOOL_OBJ) $(LIB) -o $@ -lm

validate: box2d-deps
	@$(MAKE) --no-print-directory all $(BOX2D_BIN)
	sh tools/validate.sh --carom $(BUILD)/carom --box2d $(BOX2D_BIN)

bench-box2d: box2d-deps
	@$(MAKE) --no-print-directory all $(BOX2D_BIN) $(BENCH_STEP)
	sh tools/bench-box2d.sh --bench $(BENCH_STEP) --box2d $(BOX2D_BIN)
