# mk/lean.mk -- a build of carom cut to one scene (issue 13). Included by
# the Makefile after tools/embedded/embedded.mk (it uses that fragment's
# ARM_CC, ARM_AR, EMB_CFLAGS and EMB_CPU_m4f for the Cortex-M4F column).
#
#   make lean SCENE=FILE   $(BUILD)/lean/carom_lean.h from `carom lean FILE`
#                          (rewritten only when it changes), then with it
#                          $(BUILD)/lean/libcarom.a, the profiling build
#                          $(BUILD)/lean/profile/libcarom.a and the CLI
#                          $(BUILD)/lean/carom linked with it (so `profile`
#                          works; its worlds take the header's capacities);
#                          prints text/data/bss lean against default (x86-64
#                          and, with arm-none-eabi-gcc, Cortex-M4F) and
#                          fails unless the lean CLI's final state, events
#                          and trace on FILE are byte-identical to the
#                          default CLI's
#   make lean-check        `make lean` on five example scenes (circles only;
#                          a box stack; a gas; a kinematic platform; filtered
#                          balls), each in its own directory, x86-64
#                          only, and a check that the header covers every
#                          switch of include/carom_config.h
#
# LEAN_DIR may be set to keep several lean builds apart.

LEAN_DIR ?= $(BUILD)/lean
LEAN_HDR := $(LEAN_DIR)/carom_lean.h
LEAN_OBJ := $(LIB_SRC:src/%.c=$(LEAN_DIR)/obj/%.o)
LEAN_LIB := $(LEAN_DIR)/libcarom.a
LEAN_PROF_OBJ := $(LIB_SRC:src/%.c=$(LEAN_DIR)/profile/obj/%.o)
LEAN_PROF_LIB := $(LEAN_DIR)/profile/libcarom.a
LEAN_CLI := $(LEAN_DIR)/carom
LEAN_M4F_OBJ := $(LIB_SRC:src/%.c=$(LEAN_DIR)/m4f/obj/%.o)
LEAN_M4F_LIB := $(LEAN_DIR)/m4f/libcarom.a
LEAN_INCLUDE = -include $(LEAN_HDR)
# The scenes of lean-check: circles only (no polygon code), boxes, a
# 1000-circle gas in static walls (contacts in the events method), and two
# small scenes that once broke a lean build's bits (tools/scenes/lean/).
LEAN_CHECK_SCENES := tools/scenes/cradle.scene tools/scenes/stack.scene tools/scenes/gas.scene \
	tools/scenes/lean/kinematic-drop.scene tools/scenes/lean/filtered-balls.scene
# LEAN_M4F=0 leaves out the Cortex-M4F column (lean-check does, for speed).
LEAN_M4F ?= 1
LEAN_HAVE_ARM = test "$(LEAN_M4F)" = 1 && command -v $(ARM_CC) >/dev/null 2>&1

.PHONY: lean lean-check

$(LEAN_DIR)/obj/%.o: src/%.c $(wildcard src/*.h include/*.h) $(LEAN_HDR)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(LEAN_INCLUDE) $(CFLAGS) -c $< -o $@

$(LEAN_LIB): $(LEAN_OBJ)
	rm -f $@
	ar rcs $@ $^

$(LEAN_DIR)/profile/obj/%.o: src/%.c $(wildcard src/*.h include/*.h) $(LEAN_HDR)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(PROF_FLAGS) $(LEAN_INCLUDE) $(CFLAGS) -c $< -o $@

$(LEAN_PROF_LIB): $(LEAN_PROF_OBJ)
	rm -f $@
	ar rcs $@ $^

$(LEAN_DIR)/tools/%.o: tools/%.c $(wildcard tools/*.h tools/render/*.h include/*.h) $(LEAN_HDR)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(PROF_FLAGS) $(LEAN_INCLUDE) $(TOOL_CFLAGS) -c $< -o $@

$(LEAN_CLI): $(LEAN_DIR)/tools/carom_cli.o $(LEAN_DIR)/tools/cli_options.o $(LEAN_DIR)/tools/scene.o \
             $(LEAN_DIR)/tools/render/render.o $(LEAN_PROF_LIB)
	$(CC) $(OPT) $(LDFLAGS) $^ -o $@ -lm

$(LEAN_DIR)/m4f/obj/%.o: src/%.c $(wildcard src/*.h include/*.h) $(LEAN_HDR)
	@mkdir -p $(@D)
	$(ARM_CC) $(EMB_CFLAGS) $(EMB_CPU_m4f) $(CPPFLAGS) $(LEAN_INCLUDE) -c $< -o $@

$(LEAN_M4F_LIB): $(LEAN_M4F_OBJ)
	rm -f $@
	$(ARM_AR) rcs $@ $^

# The header is remade on every `make lean` (the scene may be another one
# than last time) but replaced only when its text changes, so an unchanged
# scene rebuilds nothing.
lean: $(CLI) $(LIB)
	@test -f "$(SCENE)" || { echo "make lean: no scene file '$(SCENE)' (make lean SCENE=FILE)" >&2; exit 2; }
	@mkdir -p $(LEAN_DIR)
	$(CLI) lean $(SCENE) > $(LEAN_HDR).tmp || { rm -f $(LEAN_HDR).tmp; exit 1; }
	@if cmp -s $(LEAN_HDR).tmp $(LEAN_HDR); then rm -f $(LEAN_HDR).tmp; \
	    else mv $(LEAN_HDR).tmp $(LEAN_HDR); echo "lean: wrote $(LEAN_HDR)"; fi
	@$(MAKE) -f $(firstword $(MAKEFILE_LIST)) --no-print-directory LEAN_DIR=$(LEAN_DIR) $(LEAN_LIB) $(LEAN_CLI)
	@if $(LEAN_HAVE_ARM); then \
	    $(MAKE) -f $(firstword $(MAKEFILE_LIST)) --no-print-directory LEAN_DIR=$(LEAN_DIR) $(LEAN_M4F_LIB) $(EMB_BUILD)/m4f/libcarom.a; fi
	@sh tools/embedded/lean.sh --scene $(SCENE) --dir $(LEAN_DIR) \
	    --cli $(CLI) --lean-cli $(LEAN_CLI) --lib $(LIB) --lean-lib $(LEAN_LIB) \
	    $$($(LEAN_HAVE_ARM) && echo --m4f-lib $(EMB_BUILD)/m4f/libcarom.a --lean-m4f-lib $(LEAN_M4F_LIB))

lean-check: $(CLI) $(LIB)
	@for s in $(LEAN_CHECK_SCENES); do \
	    n=$$(basename $$s .scene); \
	    $(MAKE) -f $(firstword $(MAKEFILE_LIST)) --no-print-directory lean SCENE=$$s \
	        LEAN_DIR=$(BUILD)/lean-check/$$n LEAN_M4F=0 || exit 1; \
	    sh tools/embedded/lean.sh --switches include/carom_config.h \
	        --header $(BUILD)/lean-check/$$n/carom_lean.h || exit 1; \
	done
	@# the cradle's build has no angle helpers and no discrete method: it
	@# must refuse a scene's angle and method=discrete, naming the switch
	@d=$(BUILD)/lean-check; \
	printf 'carom-scene 1\nworld gravity=0,0 steps=2\nbody circle radius=0.5 angle=0.5\n' > $$d/angle.scene; \
	printf 'carom-scene 1\nworld gravity=0,0 steps=2 method=discrete\nbody circle radius=0.5\n' > $$d/discrete.scene; \
	for t in angle:ANGLES discrete:DISCRETE; do n=$${t%%:*}; sw=$${t#*:}; \
	    grep -q "^#define CAROM_ENABLE_$$sw 0" $$d/cradle/carom_lean.h || continue; \
	    if $$d/cradle/carom run $$d/$$n.scene > /dev/null 2> $$d/$$n.err; then \
	        echo "lean-check: FAIL: the cradle's build (CAROM_ENABLE_$$sw 0) ran $$n.scene" >&2; exit 1; fi; \
	    grep -q "CAROM_ENABLE_$$sw" $$d/$$n.err || { \
	        echo "lean-check: FAIL: refusing $$n.scene does not name CAROM_ENABLE_$$sw:" >&2; cat $$d/$$n.err >&2; exit 1; }; \
	done
	@echo "lean-check: ok: $(LEAN_CHECK_SCENES)"
