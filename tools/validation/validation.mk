# tools/validation/validation.mk -- the validation suite against Box2D 2.4.1
# and exact answers (tools/validation/, docs/validation.md). Meant to be
# included by the Makefile after tools/box2d.mk; uses its CC, BUILD, OPT,
# CPPFLAGS, CAROM_FLAGS, TOOL_CFLAGS, LIB, TOOL_OBJ, CLI and BOX2D_BIN.
#
#   make validate         every scene of tools/scenes/validation through carom
#                         (events, discrete) and Box2D; regenerates
#                         docs/validation.md and docs/validation-bounce.png;
#                         fails if a check of tools/validation/checks.txt is
#                         out of tolerance (about 10 s on 2 cores)
#   make validate-check   the same checks, with the report and figure under
#                         $(BUILD)/ so that docs/ stays as it is
#
# VALIDATE_JOBS (default: the number of CPUs) runs that many engines at once.

VALIDATE := $(BUILD)/validate
VALIDATE_SRC := $(wildcard tools/validation/*.c)
VALIDATE_JOBS ?=
# What the report says about the build of the engines it ran.
VALIDATE_BUILD = $(CC) $(shell $(CC) -dumpfullversion 2>/dev/null), OPT=$(OPT)$(if $(CAROM_FLAGS), CAROM_FLAGS=$(CAROM_FLAGS))
VALIDATE_ARGS = --carom $(CLI) --box2d $(BOX2D_BIN) --checks tools/validation/checks.txt \
    --scenes tools/scenes/validation --build '$(VALIDATE_BUILD)' \
    $(if $(VALIDATE_JOBS),--jobs $(VALIDATE_JOBS))

.PHONY: validate validate-check

# Reads scenes with tools/scene.c only (scene_load); links the library for
# carom's own masses and resolved tolerances, nothing else of it.
$(VALIDATE): $(VALIDATE_SRC) tools/validation/validate.h tools/scene.h $(wildcard include/*.h) $(FLAGS_STAMP) \
             $(TOOL_OBJ) $(LIB) | $(BUILD)/tools
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) $(VALIDATE_SRC) $(TOOL_OBJ) $(LIB) -o $@ -lm

validate: $(VALIDATE) $(CLI) $(BOX2D_BIN)
	@sh tools/ensure-deps.sh plot
	$(VALIDATE) $(VALIDATE_ARGS) --out docs/validation.md --figure docs/validation-bounce.png

validate-check: $(VALIDATE) $(CLI) $(BOX2D_BIN)
	@sh tools/ensure-deps.sh plot
	$(VALIDATE) $(VALIDATE_ARGS) --out $(BUILD)/validation.md --figure $(BUILD)/validation-bounce.png
