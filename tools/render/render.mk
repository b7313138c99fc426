# tools/render/render.mk -- the drawing code of `carom render` (render.c:
# animated SVG, gnuplot PNG frames). Included by the Makefile after CLI,
# BUILD, CPPFLAGS and TOOL_CFLAGS are set. render.o calls no carom
# function, so where it falls on build/carom's link line does not matter.

RENDER_OBJ := $(BUILD)/tools/render/render.o

$(RENDER_OBJ): tools/render/render.c tools/render/render.h $(wildcard include/*.h) $(FLAGS_STAMP)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -c $< -o $@

$(CLI) $(CLI_PLAIN): $(RENDER_OBJ)
$(BUILD)/tools/carom_cli.o: tools/render/render.h

# The pictures of docs/images/, drawn by build/carom render (needs gnuplot
# for the stills): the default scene animated, and stills: the default
# scene at 1.5 s with its impacts so far, the bullet after its first step
# under both methods, the stack after 10 s.
RENDER_TMP := $(BUILD)/render-images
BULLET_VIEW := --view=-2,-1.5,6,1.5 --size 480
# still NAME SCENE STEPS OPTIONS: the state after STEPS steps, as a PNG
render_still = rm -rf $(RENDER_TMP)/$(1) && \
    $(CLI) render $(2) --steps $(3) --every $(3) --png $(RENDER_TMP)/$(1) $(4) && \
    cp $(RENDER_TMP)/$(1)/frame-00001.png docs/images/$(1).png

.PHONY: render-images

render-images: $(CLI)
	@mkdir -p docs/images $(RENDER_TMP)
	$(CLI) render tools/scenes/default.scene --impacts -o docs/images/default.svg
	$(call render_still,default,tools/scenes/default.scene,90,--impacts)
	$(call render_still,bullet-events,tools/scenes/bullet.scene,1,--method events --impacts $(BULLET_VIEW))
	$(call render_still,bullet-discrete,tools/scenes/bullet.scene,1,--method discrete --impacts $(BULLET_VIEW))
	$(call render_still,stack,tools/scenes/stack.scene,600,--size 480)
$(BUILD)/tools/carom_cli_plain.o: tools/render/render.h
