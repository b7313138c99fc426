# tools/box2d.mk -- the Box2D 2.4.1 harness, build/carom-box2d: any carom
# scene file stepped by Box2D, with carom's CSV output, for the validation
# (tools/validation/validation.mk) and the benchmarks (tools/bench/).
# Included by the Makefile; uses its BUILD, LIB, TOOL_OBJ, CLI_OPT_OBJ, CXX and CPPFLAGS.
# Including it never needs Box2D: pkg-config is only asked when
# build/carom-box2d is built, after tools/ensure-deps.sh has had its chance
# to install libbox2d-dev and g++.
#
#   make box2d         build/carom-box2d

BOX2D_BIN  := $(BUILD)/carom-box2d
# Deferred (=): expanded only when the recipe below runs.
BOX2D_CFLAGS = $(shell pkg-config --cflags box2d 2>/dev/null)
BOX2D_LIBS   = $(shell pkg-config --libs box2d 2>/dev/null)

.PHONY: box2d box2d-deps

box2d: $(BOX2D_BIN)

box2d-deps:
	@sh tools/ensure-deps.sh box2d

$(BOX2D_BIN): tools/carom_box2d.cpp tools/scene.h tools/cli_options.h $(wildcard include/*.h) $(FLAGS_STAMP) \
              $(CLI_OPT_OBJ) $(TOOL_OBJ) $(LIB) | box2d-deps $(BUILD)/tools
	@pkg-config --exists box2d || { echo "Box2D not found (pkg-config box2d): apt-get install libbox2d-dev g++ pkg-config" >&2; exit 1; }
	$(CXX) -std=c++17 -O2 -Wall -Wextra $(CPPFLAGS) -Itools $(BOX2D_CFLAGS) \
	    tools/carom_box2d.cpp $(CLI_OPT_OBJ) $(TOOL_OBJ) $(LIB) -o $@ $(BOX2D_LIBS) -lm
