# mk/quality.mk -- what the tests cover, and the tests under the memory
# checkers (issues 14 and 10). Included by the Makefile; uses its BUILD,
# CC, CLI, deps and the rules that build $(BUILD)/carom_tests,
# $(BUILD)/carom_tests_profile and $(BUILD)/carom. Each target builds in a
# directory of its own, by running make again with BUILD, OPT and LDFLAGS
# set, so the plain build in $(BUILD) is not touched.
#
#   make coverage        the library, the unit tests and the CLI built with
#                        --coverage -O0 in $(BUILD)/cov/; runs the unit tests
#                        (both builds) and tests/cli_test.sh; gcovr's report
#                        over src/ in $(BUILD)/coverage/: index.html (a page
#                        per file) and summary.json
#   make coverage-check  make coverage, then fail if the lines or branches of
#                        src/ covered are below COV_MIN_LINES % (95) or
#                        COV_MIN_BRANCHES % (85), read from summary.json
#   make sanitize        the unit tests (both builds) and tests/cli_test.sh
#                        built with -fsanitize=address,undefined
#                        -fno-sanitize-recover=all (SAN_CC: gcc or clang,
#                        default $(CC)) in $(BUILD)/asan-COMPILER/; leaks
#                        are errors
#   make memcheck        $(CLI) under valgrind memcheck (--error-exitcode=1
#                        --leak-check=full): every tools/scenes/*.scene run
#                        in full (--events), and MEMCHECK_STEPS (30) steps
#                        of it with --trace, profile and render; the same
#                        steps of each scene of MEMCHECK_STRESS
#
# What coverage measures. The report is of the library as it ships, the
# default build (CAROM_ENABLE_PROFILE=0): $(BUILD)/cov/obj/, which the unit
# tests run. The profiling build (the CLI's library, the second unit-test
# binary) is a different program for gcov: every counted operation inlines
# a "counting or not" branch at its call site, so the same source line has
# other branches under other numbers, and merging the two builds would add
# unrelated branches together. Its own report, of the unit tests in the
# profiling build and the CLI tests, is $(BUILD)/coverage/profile/ (for
# information: validation never runs while counting, so many of its
# counting branches cannot be taken).

COV_BUILD        := $(BUILD)/cov
COV_DIR          := $(BUILD)/coverage
COV_MIN_LINES    ?= 95
COV_MIN_BRANCHES ?= 85
GCOVR            ?= gcovr
# gcc and its gcov (for clang: COV_CC=clang GCOV='llvm-cov gcov').
COV_CC           ?= gcc
GCOV             ?= gcov
# -O0: the program's lines and branches are the source's.
COV_SUBMAKE = $(MAKE) --no-print-directory BUILD='$(COV_BUILD)' CC='$(COV_CC)' \
              OPT='-O0 -g --coverage' LDFLAGS='--coverage'
COV_GCOVR = $(GCOVR) --root . --filter 'src/' --gcov-executable '$(GCOV)' \
            --html-title 'carom: coverage of src/'

SAN_CC    ?= $(CC)
# one directory per compiler: make does not rebuild when only CC changes
SAN_BUILD := $(BUILD)/asan-$(notdir $(firstword $(SAN_CC)))
SAN_FLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all
SAN_SUBMAKE = $(MAKE) --no-print-directory BUILD='$(SAN_BUILD)' CC='$(SAN_CC)' \
              OPT='-O1 -g -fno-omit-frame-pointer $(SAN_FLAGS)' \
              LDFLAGS='$(SAN_FLAGS)'
# A finding stops the program with its report on stderr and exit code 99
# (and so fails the target); leaks are reported when the program exits.
# The CLI tests keep the CLI's stderr in files and expect some runs to
# fail, so they run $(SAN_CLI): a shell wrapper (builtins only: some tests
# empty PATH) that keeps each run's stderr in $(SAN_BUILD)/stderr.PID and
# passes it on; a sanitizer report in any of them fails the target. (When
# stderr is a terminal the CLI runs as it is: a test of its progress line.)
SAN_ENV := ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1:exitcode=99 \
           UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:exitcode=99
SAN_CLI := $(SAN_BUILD)/carom-checked

VALGRIND ?= valgrind
# Add --track-origins=yes to find where an uninitialised value came from
# (it doubles the time).
MEMCHECK_FLAGS ?=
MEMCHECK = $(VALGRIND) -q --tool=memcheck --error-exitcode=1 --leak-check=full \
           --errors-for-leak-kinds=definite,indirect,possible $(MEMCHECK_FLAGS)
MEMCHECK_SCENES := $(wildcard tools/scenes/*.scene)
# A pour of 500 bodies, a pyramid, a tilted rod, a heavy body on a light
# one, a stack with a mass ratio of 100, the pi billiard (its impact chain).
MEMCHECK_STRESS ?= tools/scenes/stress/pour-500.scene \
                   tools/scenes/stress/pyramid-b20.scene \
                   tools/scenes/stress/rod-l5-tilt80.scene \
                   tools/scenes/stress/heavy-on-light-m100.scene \
                   tools/scenes/stress/stack-h10-x0-dt60-s100.scene \
                   tools/scenes/stress/pi-billiard-1e6.scene
# Steps of the stress scenes, and of the runs with --trace, profile and
# render (which exercise the CLI's own code; the plain run is complete).
MEMCHECK_STEPS ?= 30
MEMCHECK_TMP := $(BUILD)/memcheck

# The unit tests in the instrumented builds: one process (CK_FORK=no), as
# a child per test costs a leak scan or a counter dump each (under ASan
# the suite takes 30 times longer forked); any failure still fails the
# run. A test may take QUALITY_CK_TIMEOUT seconds.
QUALITY_CK_TIMEOUT ?= 600
QUALITY_CK := CK_FORK=no CK_DEFAULT_TIMEOUT=$(QUALITY_CK_TIMEOUT)

.PHONY: coverage coverage-check sanitize memcheck

# ---- coverage ---------------------------------------------------------------

coverage: deps
	@command -v $(GCOVR) >/dev/null 2>&1 || sh tools/ensure-deps.sh gcovr
	@command -v $(GCOVR) >/dev/null 2>&1 || \
	    { echo "coverage: $(GCOVR) not found (apt-get install gcovr)" >&2; exit 1; }
	@$(COV_SUBMAKE) $(COV_BUILD)/carom_tests $(COV_BUILD)/carom_tests_profile \
	    $(COV_BUILD)/carom
	@# counts of an earlier run would add up: start from zero; and drop the
	@# notes of sources that are gone (gcovr reads every .gcno it finds)
	@find $(COV_BUILD) -name '*.gcda' -exec rm -f {} +
	@for f in $(COV_BUILD)/obj/*.gcno $(COV_BUILD)/profile/obj/*.gcno; do \
	    [ -f "$$f" ] || continue; b=$$(basename "$$f" .gcno); \
	    [ -f src/$$b.c ] || rm -f "$${f%.gcno}".*; done
	$(QUALITY_CK) $(COV_BUILD)/carom_tests
	$(QUALITY_CK) $(COV_BUILD)/carom_tests_profile
	@sh tests/cli_test.sh $(COV_BUILD)/carom > $(COV_BUILD)/cli_test.log || \
	    { cat $(COV_BUILD)/cli_test.log; echo "coverage: tests/cli_test.sh failed" >&2; exit 1; }
	@echo "tests/cli_test.sh: $$(tail -n 1 $(COV_BUILD)/cli_test.log)"
	@rm -rf $(COV_DIR) && mkdir -p $(COV_DIR)/profile
	$(COV_GCOVR) --html-details $(COV_DIR)/index.html --json-summary-pretty \
	    --json-summary $(COV_DIR)/summary.json --print-summary $(COV_BUILD)/obj
	@$(COV_GCOVR) --html-details $(COV_DIR)/profile/index.html --json-summary-pretty \
	    --json-summary $(COV_DIR)/profile/summary.json $(COV_BUILD)/profile/obj
	@echo "coverage: $(COV_DIR)/index.html, $(COV_DIR)/summary.json (default build);"
	@echo "          $(COV_DIR)/profile/ (profiling build, CLI tests; not checked)"

# The check reads the totals of summary.json (python3 comes with gcovr).
define COV_CHECK_PY
import json, sys
path, min_lines, min_branches = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
with open(path) as f:
    s = json.load(f)
def pct(covered, total):
    return 100.0 * s[covered] / s[total] if s[total] else 100.0
for f in sorted(s["files"], key=lambda f: f["filename"]):
    print("  %-18s lines %6.2f %% (%4d/%4d)   branches %6.2f %% (%4d/%4d)" % (
        f["filename"], f["line_percent"], f["line_covered"], f["line_total"],
        f["branch_percent"], f["branch_covered"], f["branch_total"]))
lines = pct("line_covered", "line_total")
branches = pct("branch_covered", "branch_total")
print("src/: lines %.2f %% (minimum %g %%), branches %.2f %% (minimum %g %%)"
      % (lines, min_lines, branches, min_branches))
bad = []
if lines < min_lines:
    bad.append("lines %.2f %% < %g %%" % (lines, min_lines))
if branches < min_branches:
    bad.append("branches %.2f %% < %g %%" % (branches, min_branches))
if bad:
    sys.stderr.write("coverage-check: src/ below the minimum: %s (%s)\n"
                     % ("; ".join(bad), path))
    sys.exit(1)
endef
export COV_CHECK_PY

coverage-check: coverage
	@python3 -c "$$COV_CHECK_PY" $(COV_DIR)/summary.json $(COV_MIN_LINES) $(COV_MIN_BRANCHES)

# ---- sanitizers -------------------------------------------------------------

sanitize: deps
	@$(SAN_SUBMAKE) $(SAN_BUILD)/carom_tests $(SAN_BUILD)/carom_tests_profile \
	    $(SAN_BUILD)/carom
	$(SAN_ENV) $(QUALITY_CK) $(SAN_BUILD)/carom_tests
	$(SAN_ENV) $(QUALITY_CK) $(SAN_BUILD)/carom_tests_profile
	@rm -f $(SAN_BUILD)/stderr.*
	@{ printf '%s\n' '#!/bin/sh' \
	    '# $(SAN_BUILD)/carom with its stderr kept for make sanitize' \
	    '[ -t 2 ] && exec "$(abspath $(SAN_BUILD))/carom" "$$@"' \
	    'err=$(abspath $(SAN_BUILD))/stderr.$$$$' \
	    '"$(abspath $(SAN_BUILD))/carom" "$$@" 2>"$$err"' \
	    'rc=$$?' \
	    'while IFS= read -r line || [ -n "$$line" ]; do printf "%s\n" "$$line"; done <"$$err" >&2' \
	    'exit $$rc'; } > $(SAN_CLI) && chmod +x $(SAN_CLI)
	$(SAN_ENV) sh tests/cli_test.sh $(SAN_CLI) > $(SAN_BUILD)/cli_test.log 2>&1 || \
	    { cat $(SAN_BUILD)/cli_test.log; echo "sanitize: tests/cli_test.sh failed" >&2; exit 1; }
	@if grep -l -E 'runtime error:|Sanitizer' $(SAN_BUILD)/stderr.* 2>/dev/null; then \
	    grep -h -A 12 -E 'runtime error:|ERROR: [A-Za-z]*Sanitizer' $(SAN_BUILD)/stderr.*; \
	    echo "sanitize: the CLI runs above gave sanitizer reports" >&2; exit 1; fi
	@rm -f $(SAN_BUILD)/stderr.*
	@echo "tests/cli_test.sh: $$(tail -n 1 $(SAN_BUILD)/cli_test.log)"
	@echo "sanitize: no finding ($(SAN_CC), $(SAN_FLAGS))"

# ---- valgrind ---------------------------------------------------------------

memcheck: $(CLI)
	@command -v $(VALGRIND) >/dev/null 2>&1 || sh tools/ensure-deps.sh valgrind
	@command -v $(VALGRIND) >/dev/null 2>&1 || \
	    { echo "memcheck: $(VALGRIND) not found (apt-get install valgrind)" >&2; exit 1; }
	@rm -rf $(MEMCHECK_TMP) && mkdir -p $(MEMCHECK_TMP)
	@set -e; for s in $(MEMCHECK_SCENES); do \
	    echo "memcheck: $$s: run, run --trace, profile, render"; \
	    $(MEMCHECK) $(CLI) run $$s --events $(MEMCHECK_TMP)/events.csv \
	        > $(MEMCHECK_TMP)/out.csv; \
	    $(MEMCHECK) $(CLI) run $$s --steps $(MEMCHECK_STEPS) \
	        --trace $(MEMCHECK_TMP)/trace.csv > $(MEMCHECK_TMP)/out.csv; \
	    $(MEMCHECK) $(CLI) profile $$s --steps $(MEMCHECK_STEPS) --json \
	        > $(MEMCHECK_TMP)/profile.json; \
	    $(MEMCHECK) $(CLI) render $$s --steps $(MEMCHECK_STEPS) --impacts \
	        -o $(MEMCHECK_TMP)/scene.svg; \
	done; \
	for s in $(MEMCHECK_STRESS); do \
	    echo "memcheck: $$s: run, $(MEMCHECK_STEPS) steps"; \
	    $(MEMCHECK) $(CLI) run $$s --steps $(MEMCHECK_STEPS) \
	        --events $(MEMCHECK_TMP)/events.csv > $(MEMCHECK_TMP)/out.csv; \
	done
	@rm -rf $(MEMCHECK_TMP)
	@echo "memcheck: no error, no leak"
