/*
 * cli_options.c -- command-line options from a table (cli_options.h).
 */
#include "cli_options.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The entry of --NAME (n characters) or, n = 0, of -NAME[0]; NULL if none. */
static const cli_option *find(const cli_parser *p, const char *name, size_t n)
{
    int k;
    for (k = 0; k < p->count; ++k) {
        const cli_option *o = &p->options[k];
        if (n ? strlen(o->name) == n && strncmp(o->name, name, n) == 0
              : o->short_name != 0 && o->short_name == name[0])
            return o;
    }
    return NULL;
}

void cli_start(cli_parser *p, const char *prog, const cli_option *options, int count,
               unsigned cmd, int argc, char **argv)
{
    memset(p, 0, sizeof *p);
    p->prog = prog;
    p->options = options;
    p->count = count;
    p->cmd = cmd;
    p->argc = argc;
    p->argv = argv;
}

cli_item cli_next(cli_parser *p)
{
    const char *a, *value = NULL;
    const cli_option *o;
    char shown[64]; /* the option as the messages name it: --name or -x */

    p->opt = NULL;
    p->value = NULL;
    if (p->next >= p->argc)
        return CLI_END;
    a = p->argv[p->next++];
    if (!p->only_operands && strcmp(a, "--") == 0) {
        p->only_operands = 1;
        return cli_next(p);
    }
    if (p->only_operands || a[0] != '-' || a[1] == '\0') {
        p->value = a;
        return CLI_OPERAND;
    }
    if (a[1] == '-') {
        const char *eq = strchr(a + 2, '=');
        size_t n = eq ? (size_t)(eq - (a + 2)) : strlen(a + 2);
        o = n ? find(p, a + 2, n) : NULL;
        if (!o) {
            cli_usage_error(p->prog, "unknown option '%.*s'", (int)(n + 2), a);
            return CLI_ERROR;
        }
        if (eq)
            value = eq + 1;
        snprintf(shown, sizeof shown, "--%s", o->name);
    } else {
        o = find(p, a + 1, 0);
        /* -xVALUE and -x=VALUE; a flag's letter has nothing after it */
        if (!o || (a[2] != '\0' && !o->arg)) {
            cli_usage_error(p->prog, "unknown option '%s'", a);
            return CLI_ERROR;
        }
        if (a[2] != '\0')
            value = a[2] == '=' ? a + 3 : a + 2;
        snprintf(shown, sizeof shown, "-%c", o->short_name);
    }
    if (!(o->cmds & p->cmd)) {
        cli_usage_error(p->prog, "%s is an option of %s, not of %s", shown,
                        p->cmds_name(o->cmds), p->cmds_name(p->cmd));
        return CLI_ERROR;
    }
    if (!o->arg && value) {
        cli_usage_error(p->prog, "%s takes no value (got '%s')", shown, a);
        return CLI_ERROR;
    }
    if (o->arg && !value) {
        if (p->next >= p->argc) {
            cli_usage_error(p->prog, "%s needs a value%s%s%s", shown, *o->arg ? " (" : "",
                            o->arg, *o->arg ? ")" : "");
            return CLI_ERROR;
        }
        value = p->argv[p->next++];
    }
    if (o->arg) {
        /* "--steps 3 --steps 5" is a slip to name, not one to settle by
         * taking the last value */
        size_t k = (size_t)(o - p->options);
        if (k < CLI_MAX_OPTIONS && p->given[k]++) {
            cli_usage_error(p->prog, "--%s given twice", o->name);
            return CLI_ERROR;
        }
    }
    p->opt = o;
    p->value = value;
    return CLI_OPTION;
}

int cli_long(const cli_parser *p, long lo, long hi, const char *want, long *out)
{
    const char *v = p->value;
    char *end;
    long x;
    errno = 0;
    x = strtol(v, &end, 10);
    /* (strtol skips leading blanks; the scene reader does not) */
    if (*v == '\0' || isspace((unsigned char)*v) || *end != '\0' || errno || x < lo ||
        x > hi) {
        if (want)
            return cli_usage_error(p->prog, "--%s: want %s, got '%s'", p->opt->name, want, v);
        return cli_usage_error(p->prog, "--%s: want an integer in [%ld, %ld], got '%s'",
                               p->opt->name, lo, hi, v);
    }
    *out = x;
    return 0;
}

int cli_double(const cli_parser *p, double lo, int lo_bound, double hi, const char *want,
               double *out)
{
    const char *v = p->value;
    char *end;
    double x;
    errno = 0;
    x = strtod(v, &end);
    if (*v == '\0' || isspace((unsigned char)*v) || *end != '\0' || errno || !isfinite(x) ||
        (lo_bound == CLI_OPEN ? !(x > lo) : !(x >= lo)) || x > hi)
        return cli_usage_error(p->prog, "--%s: want %s, got '%s'", p->opt->name, want, v);
    *out = x;
    return 0;
}

int cli_usage_error(const char *prog, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "%s: ", prog);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(try '%s --help')\n", prog);
    return CLI_EXIT_USAGE;
}
