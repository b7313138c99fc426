# mk/docs.mk -- the documentation names only what the repository has.
# Included by the Makefile.
#
#   make docs-check   tools/check-docs.sh: every link, repository path and
#                     file named in README.md and docs/*.md exists, every
#                     `make TARGET` they name is listed by `make help`, the
#                     README's targets table lists every target of
#                     `make help`, and nothing points outside the repository
#
# It reads files and runs `make help`; it builds nothing and writes nothing
# under the repository.

.PHONY: docs-check

docs-check:
	sh tools/check-docs.sh --make "$(MAKE) BUILD=$(BUILD)"
