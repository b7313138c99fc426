# tools/bench/bench.mk -- make bench, make bench-quick: carom's methods,
# Box2D 2.4.1 and Box2D v3 timed side by side (issue 12), and
# docs/benchmarks.md regenerated from that run.
#
#   make bench [B2V3_DIR=/work/ext/box2d-v3]   the whole run (~10 min):
#                          docs/benchmarks.md, docs/bench-*.png
#   make bench-quick       10^2 and 10^3 bodies only, report under
#                          $(BUILD)/bench/ (docs/ untouched; ~1 min)
#   make bench-build       build/carom-bench and build/carom-bench-ops only
#
# Box2D v3 is not in Debian: build it outside the project
# (tools/box2d_v3/BUILDING.md) and pass B2V3_DIR (its install prefix), or
# B2V3_INC and B2V3_LIB. Without it the v3 column says "not built".
#
# Uses the including Makefile's CC, CXX, BUILD, LIB, PROF_LIB, CPPFLAGS and
# TOOL_CFLAGS. Box2D 2.4.1 comes from pkg-config (libbox2d-dev).

B2V3_DIR ?=
B2V3_INC ?= $(if $(B2V3_DIR),$(B2V3_DIR)/include)
B2V3_LIB ?= $(if $(B2V3_DIR),$(B2V3_DIR)/lib/libbox2d.a)
B2V3_LIBS ?= -lm -lpthread

BENCH_BIN := $(BUILD)/carom-bench
BENCH_OPS := $(BUILD)/carom-bench-ops
BENCH_DIR := $(BUILD)/bench
# The profiler's cost is measured against a library whose arithmetic layer
# is bare C operators (CR_ARITH_PLAIN), built in its own directory.
BENCH_PLAIN := $(BENCH_DIR)/carom-bench-plain
BENCH_PLAIN_LIB := $(BENCH_DIR)/plain/libcarom.a
BENCH_C := tools/bench/bench.c tools/bench/scenes.c tools/bench/engine_carom.c
BENCH_H := tools/bench/bench.h $(wildcard include/*.h) $(FLAGS_STAMP)
BENCH_B2_CFLAGS = $(shell pkg-config --cflags box2d 2>/dev/null)
BENCH_B2_LIBS = $(shell pkg-config --libs box2d 2>/dev/null)
# With Box2D v3: its engine; without: the stand-in that says "not built".
BENCH_V3_OBJ := $(if $(B2V3_LIB),$(BENCH_DIR)/engine_box2d_v3.o,$(BENCH_DIR)/engine_none_v3.o)
BENCH_V3_LIBS := $(if $(B2V3_LIB),$(B2V3_LIB) $(B2V3_LIBS))
BENCH_OUT ?= docs/benchmarks.md

.PHONY: bench bench-quick bench-build

bench-build: $(BENCH_BIN) $(BENCH_OPS) $(BENCH_PLAIN)

$(BENCH_DIR):
	mkdir -p $@

$(BENCH_DIR)/engine_box2d.o: tools/bench/engine_box2d.cpp $(BENCH_H) | $(BENCH_DIR) box2d-deps
	@pkg-config --exists box2d || { echo "Box2D 2.4.1 not found (pkg-config box2d): apt-get install libbox2d-dev g++ pkg-config" >&2; exit 1; }
	$(CXX) -std=c++17 -O2 -Wall -Wextra -Werror $(CPPFLAGS) $(BENCH_B2_CFLAGS) -c $< -o $@

$(BENCH_DIR)/engine_box2d_v3.o: tools/bench/engine_box2d_v3.c $(BENCH_H) | $(BENCH_DIR)
	@test -f "$(B2V3_INC)/box2d/box2d.h" && test -f "$(B2V3_LIB)" || { \
	    echo "Box2D v3 not found under B2V3_DIR=$(B2V3_DIR) (include/box2d/box2d.h, lib/libbox2d.a); see tools/box2d_v3/BUILDING.md" >&2; exit 1; }
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -std=c17 -DNDEBUG -isystem $(B2V3_INC) -c $< -o $@

$(BENCH_DIR)/engine_none_v3.o: tools/bench/engine_none.c $(BENCH_H) | $(BENCH_DIR)
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -DBENCH_NO_B2V3 -c $< -o $@

$(BENCH_DIR)/engine_none_ops.o: tools/bench/engine_none.c $(BENCH_H) | $(BENCH_DIR)
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -DBENCH_NO_B2V3 -DBENCH_NO_BOX2D -c $< -o $@

# Which Box2D v3 the timing build links (none, or B2V3_LIB): rewritten
# only when that changes, so that `make bench B2V3_DIR=...` after a build
# without it (or the other way round) links the binary again.
# (Its recipe runs every time: .v3-check is never made.)
BENCH_V3_STAMP := $(BENCH_DIR)/v3.stamp
$(BENCH_V3_STAMP): $(BENCH_DIR)/.v3-check | $(BENCH_DIR)
	@echo 'B2V3_LIB=$(B2V3_LIB)' | cmp -s - $@ || echo 'B2V3_LIB=$(B2V3_LIB)' > $@
$(BENCH_DIR)/.v3-check:

# The timing build: the plain library (no counters) and both Box2Ds,
# linked again when the v3 choice changes (the stamp above).
$(BENCH_BIN): $(BENCH_C) $(BENCH_H) $(BENCH_DIR)/engine_box2d.o $(BENCH_V3_OBJ) $(BENCH_V3_STAMP) $(LIB)
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -c tools/bench/bench.c -o $(BENCH_DIR)/bench.o
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -c tools/bench/scenes.c -o $(BENCH_DIR)/scenes.o
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -c tools/bench/engine_carom.c -o $(BENCH_DIR)/engine_carom.o
	$(CXX) $(BENCH_DIR)/bench.o $(BENCH_DIR)/scenes.o $(BENCH_DIR)/engine_carom.o \
	    $(BENCH_DIR)/engine_box2d.o $(BENCH_V3_OBJ) $(LIB) -o $@ \
	    $(BENCH_B2_LIBS) $(BENCH_V3_LIBS) -lm

# The operation-count build: the same driver against the profiling library.
$(BENCH_OPS): $(BENCH_C) $(BENCH_H) $(BENCH_DIR)/engine_none_ops.o $(PROF_LIB)
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) $(BENCH_C) $(BENCH_DIR)/engine_none_ops.o $(PROF_LIB) -o $@ -lm

# The plain-arithmetic library: the Makefile's own rules, in another BUILD.
$(BENCH_PLAIN_LIB): $(LIB_SRC) $(wildcard src/*.h include/*.h) $(FLAGS_STAMP)
	$(MAKE) --no-print-directory -f $(firstword $(MAKEFILE_LIST)) BUILD=$(BENCH_DIR)/plain \
	    CAROM_FLAGS='$(CAROM_FLAGS) -DCR_ARITH_PLAIN' $(BENCH_PLAIN_LIB)

$(BENCH_PLAIN): $(BENCH_C) $(BENCH_H) $(BENCH_DIR)/engine_none_ops.o $(BENCH_PLAIN_LIB)
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) $(BENCH_C) $(BENCH_DIR)/engine_none_ops.o $(BENCH_PLAIN_LIB) -o $@ -lm

BENCH_ARGS = --bench $(BENCH_BIN) --ops $(BENCH_OPS) --plain $(BENCH_PLAIN) --work $(BENCH_DIR) \
    --build "$(CC) $(OPT)$(if $(strip $(CAROM_FLAGS)), $(CAROM_FLAGS))"

bench: $(BENCH_BIN) $(BENCH_OPS) $(BENCH_PLAIN)
	@sh tools/ensure-deps.sh plot
	sh tools/bench/bench.sh $(BENCH_ARGS) --out $(BENCH_OUT)

bench-quick: $(BENCH_BIN) $(BENCH_OPS) $(BENCH_PLAIN)
	sh tools/bench/bench.sh --quick $(BENCH_ARGS) --out $(BENCH_DIR)/benchmarks-quick.md
