# tools/box2d_v3/box2d_v3.mk -- build/carom-box2d-v3: carom scene files
# through Box2D v3 (upstream erincatto/box2d), for timing and comparison
# next to build/carom and build/carom-box2d (Box2D 2.4.1).
#
# Box2D v3 is not in Debian: build it outside the project first
# (tools/box2d_v3/BUILDING.md), then point B2V3_DIR at its install prefix,
# the directory holding include/box2d/box2d.h and lib/libbox2d.a:
#
#   make B2V3_DIR=/work/ext/box2d-v3 box2d-v3
#
# To use a build tree without installing, set the two paths instead:
#
#   make B2V3_INC=/work/ext/box2d-v3-src/include \
#        B2V3_LIB=/work/ext/box2d-v3-build/src/libbox2d.a box2d-v3
#
# Uses the including Makefile's CC, BUILD, LIB, CPPFLAGS (-Iinclude) and
# TOOL_CFLAGS, and its rule for $(BUILD)/tools/scene.o. Box2D v3's headers
# need C11 or later: the harness is compiled as C17 (-std=c17 after
# TOOL_CFLAGS' -std=c99), with -isystem so that -Werror does not apply to
# them, and with -DNDEBUG because a release libbox2d.a has no
# b2InternalAssert for the headers' inline functions to call. The static
# library needs libm and, for its (unused here) thread scheduler, pthreads.

B2V3_DIR ?=
B2V3_INC ?= $(if $(B2V3_DIR),$(B2V3_DIR)/include)
B2V3_LIB ?= $(if $(B2V3_DIR),$(B2V3_DIR)/lib/libbox2d.a)
B2V3_LIBS ?= -lm -lpthread

B2V3_BIN := $(BUILD)/carom-box2d-v3
B2V3_SCENE_OBJ ?= $(BUILD)/tools/scene.o

.PHONY: box2d-v3 box2d-v3-deps

box2d-v3: $(B2V3_BIN)

box2d-v3-deps:
	@test -n "$(B2V3_INC)" && test -f "$(B2V3_INC)/box2d/box2d.h" && test -f "$(B2V3_LIB)" || { \
	    echo "Box2D v3 not found: set B2V3_DIR to its install prefix (include/box2d/box2d.h," >&2; \
	    echo "lib/libbox2d.a), or B2V3_INC and B2V3_LIB; see tools/box2d_v3/BUILDING.md" >&2; \
	    exit 1; }

$(B2V3_BIN): tools/box2d_v3/carom_box2d_v3.c tools/scene.h $(wildcard include/*.h) $(FLAGS_STAMP) \
             $(B2V3_SCENE_OBJ) $(LIB) | box2d-v3-deps
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -std=c17 -DNDEBUG -Itools -isystem $(B2V3_INC) \
	    tools/box2d_v3/carom_box2d_v3.c $(B2V3_SCENE_OBJ) $(LIB) -o $@ \
	    $(B2V3_LIB) $(B2V3_LIBS)
