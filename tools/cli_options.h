/*
 * cli_options.h -- command-line options from a table, for build/carom and
 * build/carom-box2d, so that both take options the same way and say the
 * same things about bad ones.
 *
 * An option is written --name VALUE, --name=VALUE, -x VALUE, -xVALUE or
 * -x=VALUE (a flag: --name or -x alone); "--" ends the options, and "-"
 * or any argument not starting with '-' is an operand. An option that
 * takes a value may be given once: a second time is an error ("--NAME
 * given twice"), not a silent override (a flag may repeat). Every message is
 * "PROG: what is wrong" then "(try 'PROG --help')" on stderr, and the
 * functions that print one return CLI_EXIT_USAGE for the caller to exit
 * with.
 *
 *     cli_parser p;
 *     cli_start(&p, "carom", options, OPTION_COUNT, CMD_RUN, argc, argv);
 *     while ((item = cli_next(&p)) != CLI_END) {
 *         if (item == CLI_ERROR)
 *             return CLI_EXIT_USAGE;
 *         ... p.value is an operand, or the value of option p.opt
 *     }
 */
#ifndef CAROM_CLI_OPTIONS_H
#define CAROM_CLI_OPTIONS_H

#ifdef __cplusplus
extern "C" {
#endif

/* The exit status of bad usage. */
#define CLI_EXIT_USAGE 2

/* The most options a table may have for "given twice" to be caught (the
 * parser notes each one given in a fixed array). */
#define CLI_MAX_OPTIONS 64

#if defined(__GNUC__)
#define CLI_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define CLI_PRINTF(f, a)
#endif

typedef struct cli_option {
    int id;            /* the program's name for the option */
    const char *name;  /* --name */
    char short_name;   /* -x, or 0 */
    const char *arg;   /* the value's name, "" to name it in no message;
                        * NULL: a flag, which takes no value */
    unsigned cmds;     /* bits of the commands that accept the option */
    const char *help;  /* for the program's help text (may be NULL) */
} cli_option;

typedef struct cli_parser {
    const char *prog;           /* messages start "PROG: " */
    const cli_option *options;
    int count;
    unsigned cmd;               /* the command's bit */
    /* Names a set of commands, for "--x is an option of render, not of
     * run": only needed when some option is not every command's. */
    const char *(*cmds_name)(unsigned cmds);
    int argc;
    char **argv;
    int next;                   /* index of the next argument */
    int only_operands;          /* after "--" */
    const cli_option *opt;      /* what cli_next found */
    const char *value;
    unsigned char given[CLI_MAX_OPTIONS]; /* options with a value seen, by
                                           * index in the table */
} cli_parser;

/* What cli_next found. */
typedef enum cli_item { CLI_END, CLI_OPTION, CLI_OPERAND, CLI_ERROR } cli_item;

/* Bounds of cli_double: x > lo, or x >= lo. */
enum { CLI_CLOSED = 0, CLI_OPEN = 1 };

/* Start reading argv[0 .. argc-1] (the arguments after the command) for
 * command cmd (one bit of the cmds of the table). */
void cli_start(cli_parser *p, const char *prog, const cli_option *options, int count,
               unsigned cmd, int argc, char **argv);

/* The next argument: CLI_OPTION (p->opt, and p->value: its value, NULL
 * for a flag), CLI_OPERAND (p->value), CLI_END, or CLI_ERROR after a
 * message (unknown option, option of another command, value given to a
 * flag, value missing, an option with a value given twice). */
cli_item cli_next(cli_parser *p);

/* The value of option p->opt as an integer in [lo, hi] into *out: 0, or
 * CLI_EXIT_USAGE after "--NAME: want WANT, got 'VALUE'"; WANT NULL says
 * "an integer in [lo, hi]". */
int cli_long(const cli_parser *p, long lo, long hi, const char *want, long *out);

/* The value of option p->opt as a finite number in (lo, hi] (lo_bound
 * CLI_OPEN) or [lo, hi] (CLI_CLOSED) into *out: 0, or CLI_EXIT_USAGE after
 * "--NAME: want WANT, got 'VALUE'". */
int cli_double(const cli_parser *p, double lo, int lo_bound, double hi, const char *want,
               double *out);

/* Prints "PROG: " and the message, then "(try 'PROG --help')", on
 * stderr; returns CLI_EXIT_USAGE. */
int cli_usage_error(const char *prog, const char *fmt, ...) CLI_PRINTF(2, 3);

#ifdef __cplusplus
}
#endif

#endif /* CAROM_CLI_OPTIONS_H */
