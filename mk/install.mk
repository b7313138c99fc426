# mk/install.mk -- install carom like a Debian C library (issue 14).
# Included by the Makefile; uses its BUILD, CC, CXX, CPPFLAGS, CFLAGS,
# LIB_SRC, LIB and CLI.
#
#   make shared        build/libcarom.so.X.Y.Z (soname libcarom.so.X) from
#                      -fPIC objects in build/pic/, and its two symlinks
#   make install       into $(DESTDIR)$(PREFIX) (PREFIX=/usr/local):
#                        include/carom.h, include/carom_config.h
#                        lib/libcarom.a, lib/libcarom.so.X.Y.Z,
#                        lib/libcarom.so.X -> .X.Y.Z, lib/libcarom.so -> .X
#                        lib/pkgconfig/carom.pc
#                        bin/carom
#                        share/doc/carom/README.md, share/doc/carom/docs/
#   make uninstall     remove exactly those (and the empty share/doc/carom)
#   make install-test  install into a temporary DESTDIR, build a program
#                      with pkg-config against it, link it with the shared
#                      library, run it, uninstall, check nothing is left
#   make check-cxx     the headers compile as C++ (-Wall -Wextra -Werror
#                      -pedantic, C++98 and C++17)
#
# X.Y.Z is read from CAROM_VERSION_MAJOR/MINOR/PATCH in include/carom.h
# each time make runs.

PREFIX       ?= /usr/local
BINDIR       ?= $(PREFIX)/bin
LIBDIR       ?= $(PREFIX)/lib
INCLUDEDIR   ?= $(PREFIX)/include
DOCDIR       ?= $(PREFIX)/share/doc/carom
PKGCONFIGDIR ?= $(LIBDIR)/pkgconfig
INSTALL      ?= install
CXX          ?= g++

carom_version_part = $(shell sed -n 's/^[#]define CAROM_VERSION_$(1)  *\([0-9][0-9]*\).*/\1/p' include/carom.h)
VERSION_MAJOR := $(call carom_version_part,MAJOR)
VERSION_MINOR := $(call carom_version_part,MINOR)
VERSION_PATCH := $(call carom_version_part,PATCH)
VERSION       := $(VERSION_MAJOR).$(VERSION_MINOR).$(VERSION_PATCH)

SONAME     := libcarom.so.$(VERSION_MAJOR)
SHLIB_NAME := libcarom.so.$(VERSION)
SHLIB      := $(BUILD)/$(SHLIB_NAME)
PIC_OBJ    := $(LIB_SRC:src/%.c=$(BUILD)/pic/obj/%.o)
CAROM_PC   := $(BUILD)/carom.pc

# What install copies besides the libraries (docs keep their layout, so
# the README's links into docs/ still work).
DOC_FILES   := $(wildcard docs/*.md docs/*.png)
IMAGE_FILES := $(wildcard docs/images/*)

# carom.pc: libdir and includedir relative to ${prefix} when they are
# under PREFIX, so pkg-config --define-prefix works too.
pc_rel = $(patsubst $(PREFIX)/%,$${prefix}/%,$(1))

.PHONY: shared install uninstall install-test check-cxx

shared: $(SHLIB)

$(BUILD)/pic/obj/%.o: src/%.c $(wildcard src/*.h include/*.h) $(FLAGS_STAMP)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(CFLAGS) -fPIC -c $< -o $@

# Only the carom_* functions of carom.h are exported.
$(BUILD)/pic/carom.map:
	@mkdir -p $(@D)
	printf '{\n  global: carom_*;\n  local: *;\n};\n' > $@

$(SHLIB): $(PIC_OBJ) $(BUILD)/pic/carom.map
	$(CC) -shared -Wl,-soname,$(SONAME) -Wl,--version-script=$(BUILD)/pic/carom.map \
	    -Wl,--no-undefined $(LDFLAGS) $(PIC_OBJ) -o $@ -lm
	ln -sf $(SHLIB_NAME) $(BUILD)/$(SONAME)
	ln -sf $(SONAME) $(BUILD)/libcarom.so

# Rewritten when PREFIX, LIBDIR, INCLUDEDIR or the version change (the
# recipe runs every time and replaces the file only if it differs).
$(CAROM_PC): carom.pc.in include/carom.h carom-pc-always
	@mkdir -p $(@D)
	@sed -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@LIBDIR@|$(call pc_rel,$(LIBDIR))|g' \
	    -e 's|@INCLUDEDIR@|$(call pc_rel,$(INCLUDEDIR))|g' -e 's|@VERSION@|$(VERSION)|g' \
	    carom.pc.in > $@.tmp
	@if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv $@.tmp $@; echo "wrote $@ (carom $(VERSION), prefix $(PREFIX))"; fi
carom-pc-always:

install: $(LIB) $(SHLIB) $(CLI) $(CAROM_PC)
	$(INSTALL) -d $(DESTDIR)$(INCLUDEDIR) $(DESTDIR)$(LIBDIR) $(DESTDIR)$(PKGCONFIGDIR) \
	    $(DESTDIR)$(BINDIR) $(DESTDIR)$(DOCDIR)/docs
	$(INSTALL) -m 644 include/carom.h include/carom_config.h $(DESTDIR)$(INCLUDEDIR)/
	$(INSTALL) -m 644 $(LIB) $(DESTDIR)$(LIBDIR)/libcarom.a
	$(INSTALL) -m 644 $(SHLIB) $(DESTDIR)$(LIBDIR)/$(SHLIB_NAME)
	ln -sf $(SHLIB_NAME) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libcarom.so
	$(INSTALL) -m 644 $(CAROM_PC) $(DESTDIR)$(PKGCONFIGDIR)/carom.pc
	$(INSTALL) -m 755 $(CLI) $(DESTDIR)$(BINDIR)/carom
	$(INSTALL) -m 644 README.md $(DESTDIR)$(DOCDIR)/README.md
	$(INSTALL) -m 644 $(DOC_FILES) $(DESTDIR)$(DOCDIR)/docs/
	$(if $(IMAGE_FILES),$(INSTALL) -d $(DESTDIR)$(DOCDIR)/docs/images)
	$(if $(IMAGE_FILES),$(INSTALL) -m 644 $(IMAGE_FILES) $(DESTDIR)$(DOCDIR)/docs/images/)
	@if [ -z "$(DESTDIR)" ] && [ "$$(id -u)" = 0 ] && command -v ldconfig >/dev/null 2>&1; then \
	    echo ldconfig; ldconfig || true; fi

uninstall:
	rm -f $(DESTDIR)$(INCLUDEDIR)/carom.h $(DESTDIR)$(INCLUDEDIR)/carom_config.h
	rm -f $(DESTDIR)$(LIBDIR)/libcarom.a $(DESTDIR)$(LIBDIR)/$(SHLIB_NAME) \
	    $(DESTDIR)$(LIBDIR)/$(SONAME) $(DESTDIR)$(LIBDIR)/libcarom.so
	rm -f $(DESTDIR)$(PKGCONFIGDIR)/carom.pc $(DESTDIR)$(BINDIR)/carom
	rm -f $(DESTDIR)$(DOCDIR)/README.md \
	    $(addprefix $(DESTDIR)$(DOCDIR)/docs/,$(notdir $(DOC_FILES))) \
	    $(addprefix $(DESTDIR)$(DOCDIR)/docs/images/,$(notdir $(IMAGE_FILES)))
	@for d in $(DESTDIR)$(DOCDIR)/docs/images $(DESTDIR)$(DOCDIR)/docs $(DESTDIR)$(DOCDIR); do \
	    if [ -d "$$d" ]; then rmdir "$$d" 2>/dev/null || echo "uninstall: kept $$d (not empty)"; fi; \
	done

# Everything through the real install and uninstall rules, into a fresh
# DESTDIR under build/.
INSTALL_TEST_ROOT = $(abspath $(BUILD))/install-test/root

install-test: $(LIB) $(SHLIB) $(CLI) $(CAROM_PC)
	rm -rf $(BUILD)/install-test
	@$(MAKE) --no-print-directory install DESTDIR=$(INSTALL_TEST_ROOT)
	sh tests/install_test.sh $(INSTALL_TEST_ROOT) $(PKGCONFIGDIR) $(LIBDIR) \
	    $(BINDIR) $(VERSION) $(abspath $(BUILD))/install-test
	@$(MAKE) --no-print-directory uninstall DESTDIR=$(INSTALL_TEST_ROOT)
	@left=$$(cd $(INSTALL_TEST_ROOT) && find . ! -type d); \
	if [ -n "$$left" ]; then echo "install-test: uninstall left:"; echo "$$left"; exit 1; fi; \
	echo "install-test: uninstall removed every file"

check-cxx:
	$(CXX) -std=c++98 -Wall -Wextra -Werror -pedantic -fsyntax-only $(CPPFLAGS) tests/cxx_header.cpp
	$(CXX) -std=c++17 -Wall -Wextra -Werror -pedantic -fsyntax-only $(CPPFLAGS) tests/cxx_header.cpp
