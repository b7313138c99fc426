/*
 * accuracy.h -- carom-accuracy's shared pieces: the result record that the
 * measuring modes print and the report reads, and small helpers.
 *
 * A record is one line of tab-separated key=value fields, its first field
 * the record kind:
 *
 *   run    scene=S build=B method=M den=N dt=.. steps=.. T=.. err=.. ns=..
 *          cost=.. [extra keys]
 *   bound  method=M den=N phase=.. measured=.. derived=.. ...
 *   meta   key=value (machine, compiler, build flags)
 *
 * so that measurements of several builds (compensated sums on and off,
 * TOI tolerances) can be made by separate binaries and put together by
 * `carom-accuracy report`.
 */
#ifndef CAROM_ACCURACY_H
#define CAROM_ACCURACY_H

#include <stdio.h>

#define REC_MAX_FIELDS 40

typedef struct rec {
    char kind[16];
    int n;
    char key[REC_MAX_FIELDS][24];
    char val[REC_MAX_FIELDS][160];
} rec;

void rec_init(rec *r, const char *kind);
void rec_set(rec *r, const char *key, const char *val);
void rec_num(rec *r, const char *key, double v); /* %.9g; inf/nan as such */
void rec_int(rec *r, const char *key, long v);
void rec_print(FILE *f, const rec *r);
/* 0, or -1 if the line is not a record. */
int rec_parse(const char *line, rec *r);
/* The value of key, or NULL. */
const char *rec_get(const rec *r, const char *key);
/* The value as a number; NaN if absent or not a number. */
double rec_getd(const rec *r, const char *key);

/* Progress on stderr, only when stderr is a terminal; progress_done()
 * erases the line. */
void progress(const char *fmt, ...);
void progress_done(void);

/* `carom-accuracy report` (report.c). */
int report_main(int argc, char **argv);

#endif /* CAROM_ACCURACY_H */
