# tools/accuracy/accuracy.mk -- error against run time (issue 11).
# Included by the Makefile; uses its BUILD, CC, CPPFLAGS, CFLAGS,
# TOOL_CFLAGS, LDFLAGS, CAROM_FLAGS, LIB, TOOL_OBJ, CLI and BOX2D_BIN.
#
#   make accuracy        docs/accuracy.md and docs/accuracy-*.png: every
#                        accuracy scene (tools/scenes/accuracy) with the
#                        three methods and Box2D over dt = 1/15 .. 1/3840,
#                        with the library as configured, with compensated
#                        sums off, and with smaller CAROM_TOI_TOLERANCE
#                        (each variant its own build under BUILD/accuracy/);
#                        a few minutes
#   make accuracy-check  the fast subset (bounce and projectile, three dt,
#                        three methods) against tolerances; seconds
#
# The tool, BUILD/accuracy/carom-accuracy, is linked with the library of
# its build, so a variant is the same sources built with other
# CAROM_FLAGS (a sub-make with BUILD and CAROM_FLAGS of its own).

ACC_DIR  := $(BUILD)/accuracy
ACC_SRC  := $(addprefix tools/accuracy/,accuracy.c reference.c record.c report.c)
ACC_HDR  := tools/accuracy/accuracy.h tools/accuracy/reference.h tools/scene.h \
            $(wildcard include/*.h) $(FLAGS_STAMP)
ACC_BIN  := $(ACC_DIR)/carom-accuracy
# The same tool linked with the counting library (PROF_LIB): what the
# tolerance variants need, their times are not reported.
ACC_PROF_BIN := $(ACC_DIR)/carom-accuracy-prof
# Variants: compensated sums off; smaller time-of-impact tolerances.
ACC_OFF  := $(ACC_DIR)/off
ACC_TOLS := 0.01 0.001 0.0001 0.00001

.PHONY: accuracy accuracy-check

$(ACC_BIN): $(ACC_SRC) $(ACC_HDR) $(TOOL_OBJ) $(LIB)
	@mkdir -p $(ACC_DIR)
	$(CC) $(CPPFLAGS) $(TOOL_CFLAGS) -DACC_CFLAGS='"$(CFLAGS) $(CAROM_FLAGS)"' \
	    $(ACC_SRC) $(TOOL_OBJ) $(LIB) -o $@ $(LDFLAGS) -lm

$(ACC_PROF_BIN): $(ACC_SRC) $(ACC_HDR) $(TOOL_OBJ) $(PROF_LIB)
	@mkdir -p $(ACC_DIR)
	$(CC) $(CPPFLAGS) $(PROF_FLAGS) $(TOOL_CFLAGS) -DACC_CFLAGS='"$(CFLAGS) $(CAROM_FLAGS)"' \
	    $(ACC_SRC) $(TOOL_OBJ) $(PROF_LIB) -o $@ $(LDFLAGS) -lm

accuracy: $(ACC_BIN) $(CLI) $(BOX2D_BIN)
	@sh tools/ensure-deps.sh plot
	+$(MAKE) --no-print-directory -f $(firstword $(MAKEFILE_LIST)) BUILD=$(ACC_OFF) \
	    CAROM_FLAGS='$(CAROM_FLAGS) -DCAROM_ENABLE_COMPENSATED=0' \
	    $(ACC_OFF)/carom $(ACC_OFF)/accuracy/carom-accuracy
	+@for t in $(ACC_TOLS); do \
	    $(MAKE) --no-print-directory -f $(firstword $(MAKEFILE_LIST)) BUILD=$(ACC_DIR)/tol-$$t \
	        CAROM_FLAGS="$(CAROM_FLAGS) -DCAROM_TOI_TOLERANCE=$${t}f" \
	        $(ACC_DIR)/tol-$$t/carom $(ACC_DIR)/tol-$$t/accuracy/carom-accuracy-prof || exit 1; \
	done
	$(ACC_BIN) sweep --cli $(CLI) --box2d $(BOX2D_BIN) > $(ACC_DIR)/on.tsv
	$(ACC_OFF)/accuracy/carom-accuracy sweep --methods events,first-impact \
	    --cli $(ACC_OFF)/carom > $(ACC_DIR)/off.tsv
	@for t in $(ACC_TOLS); do \
	    echo "$(ACC_DIR)/tol-$$t/accuracy/carom-accuracy-prof sweep --only spinbox ... > $(ACC_DIR)/tol-$$t.tsv"; \
	    $(ACC_DIR)/tol-$$t/accuracy/carom-accuracy-prof sweep --only spinbox \
	        --methods events --build tol-$$t --cli $(ACC_DIR)/tol-$$t/carom \
	        > $(ACC_DIR)/tol-$$t.tsv || exit 1; \
	done
	$(ACC_BIN) bound > $(ACC_DIR)/bound.tsv
	$(ACC_BIN) report --out docs/accuracy.md --figures docs $(ACC_DIR)/on.tsv \
	    $(ACC_DIR)/off.tsv $(addprefix $(ACC_DIR)/tol-,$(addsuffix .tsv,$(ACC_TOLS))) \
	    $(ACC_DIR)/bound.tsv

accuracy-check: $(ACC_BIN)
	$(ACC_BIN) check
