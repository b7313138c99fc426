/*
 * record.c -- the key=value records of carom-accuracy (accuracy.h), and
 * progress on a terminal.
 */
#include "accuracy/accuracy.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void copy(char *dst, size_t n, const char *src)
{
    size_t k = 0;
    for (; src[k] && k + 1 < n; ++k)
        dst[k] = (src[k] == '\t' || src[k] == '\n') ? ' ' : src[k];
    dst[k] = '\0';
}

void rec_init(rec *r, const char *kind)
{
    memset(r, 0, sizeof *r);
    copy(r->kind, sizeof r->kind, kind);
}

void rec_set(rec *r, const char *key, const char *val)
{
    int k;
    for (k = 0; k < r->n; ++k)
        if (strcmp(r->key[k], key) == 0)
            break;
    if (k == r->n) {
        if (r->n >= REC_MAX_FIELDS) {
            fprintf(stderr, "carom-accuracy: internal error: record full at '%s'\n", key);
            exit(2);
        }
        ++r->n;
    }
    copy(r->key[k], sizeof r->key[k], key);
    copy(r->val[k], sizeof r->val[k], val);
}

void rec_num(rec *r, const char *key, double v)
{
    char buf[40];
    snprintf(buf, sizeof buf, "%.9g", v);
    rec_set(r, key, buf);
}

void rec_int(rec *r, const char *key, long v)
{
    char buf[40];
    snprintf(buf, sizeof buf, "%ld", v);
    rec_set(r, key, buf);
}

void rec_print(FILE *f, const rec *r)
{
    int k;
    fputs(r->kind, f);
    for (k = 0; k < r->n; ++k)
        fprintf(f, "\t%s=%s", r->key[k], r->val[k]);
    fputc('\n', f);
}

int rec_parse(const char *line, rec *r)
{
    const char *p = line, *tab;
    size_t len;
    char field[160];
    tab = strchr(p, '\t');
    len = tab ? (size_t)(tab - p) : strcspn(p, "\n");
    if (len == 0 || len >= sizeof r->kind || line[0] == '#')
        return -1;
    memcpy(field, p, len);
    field[len] = '\0';
    rec_init(r, field);
    while (tab) {
        char *eq;
        p = tab + 1;
        tab = strchr(p, '\t');
        len = tab ? (size_t)(tab - p) : strcspn(p, "\n");
        if (len >= sizeof field)
            return -1;
        memcpy(field, p, len);
        field[len] = '\0';
        eq = strchr(field, '=');
        if (!eq)
            return -1;
        *eq = '\0';
        rec_set(r, field, eq + 1);
    }
    return 0;
}

const char *rec_get(const rec *r, const char *key)
{
    int k;
    for (k = 0; k < r->n; ++k)
        if (strcmp(r->key[k], key) == 0)
            return r->val[k];
    return NULL;
}

double rec_getd(const rec *r, const char *key)
{
    const char *v = rec_get(r, key);
    char *end;
    double x;
    if (!v)
        return (double)NAN;
    x = strtod(v, &end);
    return (end == v || *end) ? (double)NAN : x;
}

static int shown;

void progress(const char *fmt, ...)
{
    va_list ap;
    if (!isatty(2))
        return;
    va_start(ap, fmt);
    fputs("\r\033[K", stderr);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fflush(stderr);
    shown = 1;
}

void progress_done(void)
{
    if (shown && isatty(2)) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
    }
    shown = 0;
}
