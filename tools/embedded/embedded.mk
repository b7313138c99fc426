# tools/embedded/embedded.mk -- the library on emulated Cortex-M (included
# from the top-level Makefile; tools/embedded/README.md explains it all).
#
#   make check-embedded           the scene suite on mps2-an386 (Cortex-M4F,
#                                 hard float), mps2-an385 (Cortex-M3, soft
#                                 float) and microbit (Cortex-M0, soft float,
#                                 16 KB RAM: the reduced suite; the whole
#                                 suite runs its code on mps2-an385) under
#                                 qemu-system-arm must print the hashes of the
#                                 x86-64 build, then embedded-lean8k; skips
#                                 when qemu-system-arm or arm-none-eabi-gcc is
#                                 missing
#   make check-embedded-negative  the M4F firmware built with
#                                 -ffp-contract=fast (fused multiply-add) must
#                                 make the same comparison fail
#   make embedded-insn            instructions executed per run on the M4F
#                                 (QEMU plugin) against
#                                 `carom profile --weights cortex-m4f`
#   make embedded-calibrate       fit `carom profile --calibration` to the
#                                 instructions counted on the M4F, per phase
#                                 (writes tools/embedded/cortex-m4f.cal)
#   make embedded-lean8k          the bounce scene and the 5-box stack, each
#                                 with its `carom lean` switches and
#                                 capacities, in 8 KB of world on the
#                                 micro:bit (Cortex-M0): same results as x86-64
#   make embedded-doc             regenerate docs/embedded.md (targets,
#                                 footprint per configuration, stack, RAM,
#                                 8 KB, calibration), a few minutes
#   make embedded-size            text/data/bss of the library per core
#   make embedded                 build everything above, run nothing

EMB_DIR   := tools/embedded
EMB_BUILD := $(BUILD)/embedded
ARM_CC    ?= arm-none-eabi-gcc
ARM_AR    ?= arm-none-eabi-ar
QEMU_ARM  ?= qemu-system-arm

# The project's strict flags, as tools/check-cross.sh uses them.
EMB_CFLAGS := $(WARN) -O2

# Library builds: the CPU flags of each.
EMB_CPU_m4f := -mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard
EMB_CPU_m3  := -mcpu=cortex-m3 -mthumb -mfloat-abi=soft
EMB_CPU_m0  := -mcpu=cortex-m0 -mthumb -mfloat-abi=soft
# The negative test: the M4F build with contraction into VFMA allowed
# (the later -ffp-contract wins over the project's =off).
EMB_CPU_m4f-fma := $(EMB_CPU_m4f) -ffp-contract=fast
# The calibration's phase firmware: the M4F build with the op counters.
EMB_CPU_m4f-prof := $(EMB_CPU_m4f) $(PROF_FLAGS)
EMB_LIBS := m4f m3 m0 m4f-fma m4f-prof

# Firmware builds: library, QEMU board, linker script, world buffer, and
# whether only the reduced suite (scenes marked small in suite.list) runs.
#  m4f      mps2-an386, Cortex-M4F, hard float
#  m3       mps2-an385, Cortex-M3, soft float
#  m0       microbit (nRF51), Cortex-M0, soft float, 16 KB of RAM: what is
#           left beside a 3 KB stack (the link fails if it does not fit)
#  m0-mps2  the same Cortex-M0 code on mps2-an385, for the scenes that do
#           not fit the micro:bit (QEMU's mps2 boards take no other CPU;
#           ARMv6-M code runs unchanged on the Cortex-M3)
#  m4f-fma  the negative test
#  m0-sizes the Cortex-M0 library printing what worlds cost in memory
#           (sizes.c; embedded-doc) instead of running the suite
#  m4f-phase  the calibration's phase firmware (embedded-calibrate): the
#           profiling M4F library, with every phase switch and step marked
#           for the instruction counter (fw_main.c, FW_PHASES)
EMB_FW_LIB_m4f := m4f
EMB_FW_LIB_m3  := m3
EMB_FW_LIB_m0  := m0
EMB_FW_LIB_m0-mps2 := m0
EMB_FW_LIB_m4f-fma := m4f-fma
EMB_FW_LIB_m4f-phase := m4f-prof
EMB_FW_LIB_m0-sizes := m0

EMB_BOARD_m4f := mps2-an386
EMB_BOARD_m3  := mps2-an385
EMB_BOARD_m0  := microbit
EMB_BOARD_m0-mps2 := mps2-an385
EMB_BOARD_m4f-fma := mps2-an386
EMB_BOARD_m4f-phase := mps2-an386
EMB_BOARD_m0-sizes := microbit

EMB_LD_m4f := mps2.ld
EMB_LD_m3  := mps2.ld
EMB_LD_m0  := microbit.ld
EMB_LD_m0-mps2 := mps2.ld
EMB_LD_m4f-fma := mps2.ld
EMB_LD_m4f-phase := mps2.ld
EMB_LD_m0-sizes := microbit.ld

EMB_WORLD_m4f := 524288
EMB_WORLD_m3  := 524288
EMB_WORLD_m0  := 12800
EMB_WORLD_m0-mps2 := 524288
EMB_WORLD_m4f-fma := 524288
EMB_WORLD_m4f-phase := 524288
EMB_WORLD_m0-sizes := 16
EMB_FWFLAGS_m0-sizes := -DFW_SIZES=1
EMB_SMALL_m0  := 1
EMB_FWFLAGS_m4f-phase := -DFW_PHASES=1
EMB_LDFLAGS_m4f-phase := -Wl,--wrap=cr_prof_phase -Wl,--wrap=carom_world_step

EMB_TARGETS := m4f m3 m0 m0-mps2

EMB_LIB_SRC := $(wildcard src/*.c)
EMB_FW_SRC  := $(EMB_DIR)/suite.c $(EMB_DIR)/sizes.c $(EMB_DIR)/fw_main.c $(EMB_DIR)/startup.c
EMB_HEADERS := $(wildcard src/*.h include/*.h) $(FLAGS_STAMP) $(EMB_DIR)/suite.h $(EMB_DIR)/fw.h
EMB_SCENES  := $(shell awk '!/^[ \t]*(\#|$$)/ {print $$2}' $(EMB_DIR)/suite.list 2>/dev/null)

.PHONY: embedded embedded-host check-embedded check-embedded-negative embedded-insn embedded-size \
        embedded-calibrate embedded-lean8k embedded-doc

# ---- host side: the generator, the suite's data, the x86-64 runner ------------

$(EMB_BUILD)/gen_suite: $(EMB_DIR)/gen_suite.c $(EMB_DIR)/suite.c $(EMB_DIR)/suite.h \
                        $(TOOL_OBJ) $(LIB) $(wildcard tools/*.h include/*.h) $(FLAGS_STAMP)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -I$(EMB_DIR) $(EMB_DIR)/gen_suite.c \
	    $(EMB_DIR)/suite.c $(TOOL_OBJ) $(LIB) -o $@ $(LDFLAGS) -lm

$(EMB_BUILD)/suite_data.c: $(EMB_BUILD)/gen_suite $(EMB_DIR)/suite.list $(EMB_SCENES)
	$(EMB_BUILD)/gen_suite $(EMB_DIR)/suite.list $@

$(EMB_BUILD)/suite_host: $(EMB_DIR)/host_main.c $(EMB_DIR)/suite.c $(EMB_DIR)/sizes.c \
                         $(EMB_BUILD)/suite_data.c \
                         $(EMB_DIR)/suite.h $(LIB)
	$(CC) $(CPPFLAGS) $(CFLAGS) -I$(EMB_DIR) $(EMB_DIR)/host_main.c $(EMB_DIR)/suite.c \
	    $(EMB_DIR)/sizes.c $(EMB_BUILD)/suite_data.c $(LIB) -o $@ $(LDFLAGS) -lm

$(EMB_BUILD)/insn_count.so: $(EMB_DIR)/insn_count.c
	@mkdir -p $(@D)
	$(CC) -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Werror -O2 -shared -fPIC \
	    -fvisibility=hidden $< -o $@

$(EMB_BUILD)/calibrate: $(EMB_DIR)/calibrate.c
	@mkdir -p $(@D)
	$(CC) $(TOOL_CFLAGS) $< -o $@ -lm

embedded-host: $(EMB_BUILD)/suite_host

# ---- the library per core, one firmware per target -----------------------------
# $(1): library build (m4f, m3, m0, m4f-fma)
define EMB_LIB_RULES
$(EMB_BUILD)/$(1)/lib/%.o: src/%.c $(EMB_HEADERS)
	@mkdir -p $$(@D)
	$(ARM_CC) $(EMB_CFLAGS) $(EMB_CPU_$(1)) $(CPPFLAGS) -c $$< -o $$@

$(EMB_BUILD)/$(1)/libcarom.a: $(EMB_LIB_SRC:src/%.c=$(EMB_BUILD)/$(1)/lib/%.o)
	rm -f $$@
	$(ARM_AR) rcs $$@ $$^
endef
$(foreach l,$(EMB_LIBS),$(eval $(call EMB_LIB_RULES,$(l))))

# $(1): firmware target (m4f, m3, m0, m0-mps2, m4f-fma)
define EMB_FW_RULES
$(EMB_BUILD)/$(1)/fw/%.o: $(EMB_DIR)/%.c $(EMB_HEADERS)
	@mkdir -p $$(@D)
	$(ARM_CC) $(EMB_CFLAGS) -g $(EMB_CPU_$(EMB_FW_LIB_$(1))) $(CPPFLAGS) -I$(EMB_DIR) \
	    -DFW_WORLD_BYTES=$(EMB_WORLD_$(1)) -DFW_SMALL=$(or $(EMB_SMALL_$(1)),0) \
	    -DFW_BOARD='"$(EMB_BOARD_$(1))"' $(EMB_FWFLAGS_$(1)) -c $$< -o $$@

$(EMB_BUILD)/$(1)/fw/suite_data.o: $(EMB_BUILD)/suite_data.c $(EMB_HEADERS)
	@mkdir -p $$(@D)
	$(ARM_CC) $(EMB_CFLAGS) $(EMB_CPU_$(EMB_FW_LIB_$(1))) $(CPPFLAGS) -I$(EMB_DIR) -c $$< -o $$@

$(EMB_BUILD)/$(1)/fw.elf: $(EMB_FW_SRC:$(EMB_DIR)/%.c=$(EMB_BUILD)/$(1)/fw/%.o) \
                          $(EMB_BUILD)/$(1)/fw/suite_data.o \
                          $(EMB_BUILD)/$(EMB_FW_LIB_$(1))/libcarom.a \
                          $(EMB_DIR)/link.ld $(EMB_DIR)/$(EMB_LD_$(1))
	$(ARM_CC) $(EMB_CPU_$(EMB_FW_LIB_$(1))) $(EMB_LDFLAGS_$(1)) -nostartfiles --specs=nano.specs -L$(EMB_DIR) \
	    -T $(EMB_DIR)/$(EMB_LD_$(1)) -Wl,--gc-sections -Wl,-Map=$(EMB_BUILD)/$(1)/fw.map \
	    $(EMB_FW_SRC:$(EMB_DIR)/%.c=$(EMB_BUILD)/$(1)/fw/%.o) \
	    $(EMB_BUILD)/$(1)/fw/suite_data.o $(EMB_BUILD)/$(EMB_FW_LIB_$(1))/libcarom.a -lm -o $$@
endef
$(foreach t,$(EMB_TARGETS) m4f-fma m4f-phase m0-sizes,$(eval $(call EMB_FW_RULES,$(t))))

embedded: $(EMB_BUILD)/suite_host $(foreach t,$(EMB_TARGETS),$(EMB_BUILD)/$(t)/fw.elf)

# ---- checks -------------------------------------------------------------------------------

EMB_HAVE_TOOLS = command -v $(ARM_CC) >/dev/null 2>&1 && command -v $(QEMU_ARM) >/dev/null 2>&1

check-embedded:
	@if $(EMB_HAVE_TOOLS); then \
	    start=$$(date +%s); \
	    $(MAKE) -f $(firstword $(MAKEFILE_LIST)) --no-print-directory embedded && \
	    QEMU_ARM=$(QEMU_ARM) sh $(EMB_DIR)/check-embedded.sh $(EMB_BUILD) \
	        $(foreach t,$(EMB_TARGETS),$(t):$(EMB_BOARD_$(t)):$(if $(EMB_SMALL_$(t)),small,full)) && \
	    $(MAKE) -f $(firstword $(MAKEFILE_LIST)) --no-print-directory embedded-lean8k && \
	    echo "check-embedded: $$(( $$(date +%s) - start )) s in all"; \
	else \
	    echo "check-embedded: skipped: needs $(ARM_CC) and $(QEMU_ARM) (Debian: gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm)"; \
	fi

check-embedded-negative:
	@if $(EMB_HAVE_TOOLS); then \
	    $(MAKE) -f $(firstword $(MAKEFILE_LIST)) --no-print-directory $(EMB_BUILD)/suite_host $(EMB_BUILD)/m4f-fma/fw.elf && \
	    QEMU_ARM=$(QEMU_ARM) sh $(EMB_DIR)/check-embedded.sh --expect-mismatch $(EMB_BUILD) \
	        m4f-fma:$(EMB_BOARD_m4f-fma):full; \
	else \
	    echo "check-embedded-negative: skipped: needs $(ARM_CC) and $(QEMU_ARM)"; \
	fi

embedded-insn: $(EMB_BUILD)/suite_host $(EMB_BUILD)/m4f/fw.elf $(EMB_BUILD)/insn_count.so $(CLI)
	QEMU_ARM=$(QEMU_ARM) sh $(EMB_DIR)/insn-profile.sh $(EMB_BUILD) $(CLI) $(EMB_DIR)/suite.list \
	    $(EMB_CAL)

# ---- 8 KB of world on the micro:bit: lean builds of two scenes -----------------
# For each NAME:SCENE: `carom lean SCENE` -> a Cortex-M0 library with that
# header, and a micro:bit firmware that runs the scene (events method)
# with the header's capacities in a world buffer of EMB_LEAN8K_BYTES; its
# result must equal the default x86-64 build's.
EMB_LEAN8K := bounce:tools/embedded/scenes/bounce.scene stack:tools/scenes/stack.scene
EMB_LEAN8K_BYTES := 8192
EMB_LEAN8K_NAMES := $(foreach p,$(EMB_LEAN8K),$(firstword $(subst :, ,$(p))))

# $(1): name, $(2): scene file
define EMB_LEAN8K_RULES
$(EMB_BUILD)/lean8k/$(1)/carom_lean.h: $(2) $(CLI)
	@mkdir -p $$(@D)
	$(CLI) lean $(2) > $$@.tmp && mv $$@.tmp $$@

$(EMB_BUILD)/lean8k/$(1)/suite.list: $(EMB_DIR)/embedded.mk
	@mkdir -p $$(@D)
	echo "$(1) $(2) - small" > $$@

$(EMB_BUILD)/lean8k/$(1)/suite_data.c: $(EMB_BUILD)/gen_suite $(EMB_BUILD)/lean8k/$(1)/suite.list $(2)
	$(EMB_BUILD)/gen_suite $(EMB_BUILD)/lean8k/$(1)/suite.list $$@

$(EMB_BUILD)/lean8k/$(1)/lib/%.o: src/%.c $(EMB_HEADERS) $(EMB_BUILD)/lean8k/$(1)/carom_lean.h
	@mkdir -p $$(@D)
	$(ARM_CC) $(EMB_CFLAGS) $(EMB_CPU_m0) $(CPPFLAGS) \
	    -include $(EMB_BUILD)/lean8k/$(1)/carom_lean.h -c $$< -o $$@

$(EMB_BUILD)/lean8k/$(1)/libcarom.a: $(EMB_LIB_SRC:src/%.c=$(EMB_BUILD)/lean8k/$(1)/lib/%.o)
	rm -f $$@
	$(ARM_AR) rcs $$@ $$^

$(EMB_BUILD)/lean8k/$(1)/fw/%.o: $(EMB_DIR)/%.c $(EMB_HEADERS) $(EMB_BUILD)/lean8k/$(1)/carom_lean.h
	@mkdir -p $$(@D)
	$(ARM_CC) $(EMB_CFLAGS) -g $(EMB_CPU_m0) $(CPPFLAGS) -I$(EMB_DIR) \
	    -include $(EMB_BUILD)/lean8k/$(1)/carom_lean.h -DSUITE_EVENTS_ONLY=1 \
	    -DFW_WORLD_BYTES=$(EMB_LEAN8K_BYTES) -DFW_SMALL=0 -DFW_BOARD='"microbit"' -c $$< -o $$@

$(EMB_BUILD)/lean8k/$(1)/fw/suite_data.o: $(EMB_BUILD)/lean8k/$(1)/suite_data.c $(EMB_HEADERS) \
                                          $(EMB_BUILD)/lean8k/$(1)/carom_lean.h
	@mkdir -p $$(@D)
	$(ARM_CC) $(EMB_CFLAGS) $(EMB_CPU_m0) $(CPPFLAGS) -I$(EMB_DIR) \
	    -include $(EMB_BUILD)/lean8k/$(1)/carom_lean.h -c $$< -o $$@

$(EMB_BUILD)/lean8k/$(1)/fw.elf: $(EMB_FW_SRC:$(EMB_DIR)/%.c=$(EMB_BUILD)/lean8k/$(1)/fw/%.o) \
                                 $(EMB_BUILD)/lean8k/$(1)/fw/suite_data.o \
                                 $(EMB_BUILD)/lean8k/$(1)/libcarom.a $(EMB_DIR)/link.ld \
                                 $(EMB_DIR)/microbit.ld
	$(ARM_CC) $(EMB_CPU_m0) -nostartfiles --specs=nano.specs -L$(EMB_DIR) \
	    -T $(EMB_DIR)/microbit.ld -Wl,--gc-sections -Wl,-Map=$(EMB_BUILD)/lean8k/$(1)/fw.map \
	    $(EMB_FW_SRC:$(EMB_DIR)/%.c=$(EMB_BUILD)/lean8k/$(1)/fw/%.o) \
	    $(EMB_BUILD)/lean8k/$(1)/fw/suite_data.o $(EMB_BUILD)/lean8k/$(1)/libcarom.a -lm -o $$@

$(EMB_BUILD)/lean8k/$(1)/host: $(EMB_DIR)/host_main.c $(EMB_DIR)/suite.c \
                               $(EMB_BUILD)/lean8k/$(1)/suite_data.c $(EMB_DIR)/suite.h $(LIB)
	$(CC) $(CPPFLAGS) $(CFLAGS) -I$(EMB_DIR) -DSUITE_EVENTS_ONLY=1 $(EMB_DIR)/host_main.c \
	    $(EMB_DIR)/suite.c $(EMB_DIR)/sizes.c $(EMB_BUILD)/lean8k/$(1)/suite_data.c $(LIB) \
	    -o $$@ $(LDFLAGS) -lm
endef
$(foreach p,$(EMB_LEAN8K),$(eval $(call EMB_LEAN8K_RULES,$(firstword $(subst :, ,$(p))),$(lastword $(subst :, ,$(p))))))

embedded-lean8k:
	@if $(EMB_HAVE_TOOLS); then \
	    $(MAKE) -f $(firstword $(MAKEFILE_LIST)) --no-print-directory \
	        $(foreach n,$(EMB_LEAN8K_NAMES),$(EMB_BUILD)/lean8k/$(n)/fw.elf $(EMB_BUILD)/lean8k/$(n)/host) && \
	    QEMU_ARM=$(QEMU_ARM) sh $(EMB_DIR)/lean8k.sh $(EMB_BUILD)/lean8k $(EMB_LEAN8K_BYTES) $(EMB_LEAN8K_NAMES); \
	else \
	    echo "embedded-lean8k: skipped: needs $(ARM_CC) and $(QEMU_ARM)"; \
	fi

# docs/embedded.md, every number measured anew (a few minutes; rewrites
# tools/embedded/cortex-m4f.cal too).
embedded-doc: $(CLI) $(LIB)
	@$(EMB_HAVE_TOOLS) || { echo "embedded-doc: needs $(ARM_CC) and $(QEMU_ARM)" >&2; exit 1; }
	$(MAKE) -f $(firstword $(MAKEFILE_LIST)) --no-print-directory embedded \
	    $(EMB_BUILD)/m4f-fma/fw.elf $(EMB_BUILD)/m4f-phase/fw.elf $(EMB_BUILD)/m0-sizes/fw.elf \
	    $(EMB_BUILD)/insn_count.so $(EMB_BUILD)/calibrate \
	    $(foreach n,$(EMB_LEAN8K_NAMES),$(EMB_BUILD)/lean8k/$(n)/fw.elf $(EMB_BUILD)/lean8k/$(n)/host)
	BUILD=$(BUILD) CLI=$(CLI) CC="$(CC)" HOST_FLAGS="$(CFLAGS) $(CAROM_FLAGS)" ARM_CC=$(ARM_CC) \
	    M4F_FLAGS="$(EMB_CFLAGS) $(EMB_CPU_m4f) $(CAROM_FLAGS)" \
	    M0_FLAGS="$(EMB_CFLAGS) $(EMB_CPU_m0) $(CAROM_FLAGS)" M4F_CPU="$(EMB_CPU_m4f)" \
	    QEMU_ARM=$(QEMU_ARM) \
	    sh $(EMB_DIR)/embedded-doc.sh docs/embedded.md

# The calibration of `carom profile --calibration` (tools/embedded/cortex-m4f.cal):
# the plain and the phase M4F firmware counted under qemu, fitted.
EMB_CAL := $(EMB_DIR)/cortex-m4f.cal
embedded-calibrate: $(EMB_BUILD)/m4f/fw.elf $(EMB_BUILD)/m4f-phase/fw.elf \
                    $(EMB_BUILD)/insn_count.so $(EMB_BUILD)/calibrate $(CLI)
	QEMU_ARM=$(QEMU_ARM) sh $(EMB_DIR)/calibrate.sh $(EMB_BUILD) $(CLI) $(EMB_DIR)/suite.list $(EMB_CAL)

embedded-size: $(foreach l,m4f m3 m0,$(EMB_BUILD)/$(l)/libcarom.a)
	@for t in m4f m3 m0; do \
	    arm-none-eabi-size -t $(EMB_BUILD)/$$t/libcarom.a | tail -n 1 | \
	        awk -v t=$$t '{printf "%-4s library: text %6d  data %4d  bss %4d\n", t, $$1, $$2, $$3}'; \
	done
