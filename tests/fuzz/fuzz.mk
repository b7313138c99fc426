# tests/fuzz/fuzz.mk -- libFuzzer harnesses of carom (tests/fuzz/README.md).
#
#   make fuzz [FUZZ_SECONDS=N]  build the harnesses into $(BUILD)/fuzz/, fuzz
#                               each for N s (default 30) on a work copy of
#                               its seed corpus, then replay the seeds and
#                               tests/fuzz/crashers/; fails on any finding
#   make fuzz-check             reproducible fuzzing (make check): seed
#                               FUZZ_SEED (1), a fixed number of inputs per
#                               harness (fuzz.sh check_runs, ~30 s each) at
#                               most FUZZ_SECONDS (60) each; then the replay
#   make fuzz-regress           only the replay (seconds)
#   make fuzz-build             only build the harnesses
#   make fuzz-clean             remove $(BUILD)/fuzz/
#
# Without clang or libFuzzer, fuzz and fuzz-regress print why and succeed
# (FUZZ_REQUIRE=1 makes that an error). Include this file from the Makefile
# or name it: make -f Makefile -f tests/fuzz/fuzz.mk fuzz FUZZ_SECONDS=10.
# It also works alone: make -f tests/fuzz/fuzz.mk fuzz-regress.
# Run make from the repository root.

FUZZ_MK := $(lastword $(MAKEFILE_LIST))

BUILD ?= build
FUZZ_CC ?= clang
FUZZ_SECONDS ?= 30
FUZZ_REQUIRE ?=
CAROM_FLAGS ?=
FUZZ_OUT := $(BUILD)/fuzz
FUZZ_SH := sh tests/fuzz/fuzz.sh
FUZZ_SAN := -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
FUZZ_CFLAGS ?= -std=c99 -O1 -g -fno-omit-frame-pointer -ffp-contract=off \
               -Wall -Wextra
FUZZ_CPPFLAGS := -Iinclude $(CAROM_FLAGS)

FUZZ_HARNESSES := fuzz_scene_parse fuzz_scene_run fuzz_api
FUZZ_BINS := $(FUZZ_HARNESSES:%=$(FUZZ_OUT)/%)
FUZZ_LIB_OBJ := $(patsubst src/%.c,$(FUZZ_OUT)/obj/%.o,$(wildcard src/*.c))
FUZZ_SCENE_OBJ := $(FUZZ_OUT)/tools/scene.o
FUZZ_HEADERS := $(wildcard src/*.h include/*.h)

# Forward the settings to the sub-make (it reads this file alone).
FUZZ_SUBMAKE = $(MAKE) --no-print-directory -f $(FUZZ_MK) BUILD='$(BUILD)' \
               FUZZ_CC='$(FUZZ_CC)' CAROM_FLAGS='$(CAROM_FLAGS)'
FUZZ_SKIP = echo "$@: skipped: '$(FUZZ_CC)' cannot build a libFuzzer program \
(-fsanitize=fuzzer,address,undefined); install clang and libclang-rt-dev \
(Debian: apt-get install clang libclang-rt-dev)"; test -z "$(FUZZ_REQUIRE)"

.PHONY: fuzz fuzz-check fuzz-regress fuzz-build fuzz-clean

fuzz:
	@if $(FUZZ_SH) probe '$(FUZZ_CC)' '$(FUZZ_OUT)'; then \
	    $(FUZZ_SUBMAKE) fuzz-build && \
	    $(FUZZ_SH) run '$(FUZZ_OUT)' '$(FUZZ_SECONDS)'; \
	else $(FUZZ_SKIP); fi

FUZZ_SEED ?= 1
fuzz-check:
	@if $(FUZZ_SH) probe '$(FUZZ_CC)' '$(FUZZ_OUT)'; then \
	    $(FUZZ_SUBMAKE) fuzz-build && \
	    $(FUZZ_SH) run '$(FUZZ_OUT)' '$(if $(filter command line,$(origin FUZZ_SECONDS)),$(FUZZ_SECONDS),60)' '$(FUZZ_SEED)'; \
	else $(FUZZ_SKIP); fi

fuzz-regress:
	@if $(FUZZ_SH) probe '$(FUZZ_CC)' '$(FUZZ_OUT)'; then \
	    $(FUZZ_SUBMAKE) fuzz-build && \
	    $(FUZZ_SH) replay '$(FUZZ_OUT)'; \
	else $(FUZZ_SKIP); fi

# (the objects are named so that make keeps them between builds)
fuzz-build: $(FUZZ_BINS) $(FUZZ_LIB_OBJ) $(FUZZ_SCENE_OBJ)
	@:

# The library and the scene reader with the harnesses' sanitizers and
# coverage instrumentation (-fsanitize=fuzzer on -c instruments, no main).
$(FUZZ_OUT)/obj/%.o: src/%.c $(FUZZ_HEADERS) | $(FUZZ_OUT)/obj
	$(FUZZ_CC) $(FUZZ_CPPFLAGS) $(FUZZ_SAN) $(FUZZ_CFLAGS) -c $< -o $@

$(FUZZ_SCENE_OBJ): tools/scene.c tools/scene.h $(FUZZ_HEADERS) | $(FUZZ_OUT)/tools
	$(FUZZ_CC) $(FUZZ_CPPFLAGS) -Itools -D_POSIX_C_SOURCE=200809L $(FUZZ_SAN) \
	    $(FUZZ_CFLAGS) -c $< -o $@

$(FUZZ_OUT)/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz_common.h tools/scene.h \
                    $(FUZZ_LIB_OBJ) $(FUZZ_SCENE_OBJ)
	$(FUZZ_CC) $(FUZZ_CPPFLAGS) -Itools -D_POSIX_C_SOURCE=200809L $(FUZZ_SAN) \
	    $(FUZZ_CFLAGS) $< $(FUZZ_LIB_OBJ) $(FUZZ_SCENE_OBJ) -o $@ -lm

$(FUZZ_OUT)/obj $(FUZZ_OUT)/tools:
	mkdir -p $@

fuzz-clean:
	rm -rf $(FUZZ_OUT)
