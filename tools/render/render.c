/*
 * render.c -- animated SVG and gnuplot PNG frames of a recorded carom run.
 * See render.h. A tool: allocates, uses libm and POSIX.
 */
#include "render/render.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

/* Pixels above the view for the time label (and one more line for the
 * note), the narrowest view that still fits the label, the margin around
 * the bodies as a share of the larger extent, and how long an impact
 * marker stays (simulated seconds, at least one frame). */
#define BAND_PX 24
#define NOTE_PX 18
#define MIN_WIDTH_PX 260
#define MARGIN_SHARE 0.04
#define MARKER_SECONDS 0.25
#define MARKER_PX 4.0

static const char *const palette[] = {
    "#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
    "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#8cd17d"
};
#define PALETTE_SIZE (sizeof palette / sizeof palette[0])
#define STATIC_FILL "#c8c8c8"
#define STATIC_STROKE "#555555"
#define BODY_STROKE "#222222"
#define MARKER_FILL "#d62728"

/* World-to-pixel mapping: px = (x - x0) s, py = top + (y1 - y) s. */
typedef struct view {
    double x0, y1, s;
    int width, height, top;
} view;

static double px_x(const view *v, double x) { return (x - v->x0) * v->s; }
static double px_y(const view *v, double y) { return v->top + (v->y1 - y) * v->s; }

static void world_vertex(const render_shape *sh, const render_pose *p, int i,
                         double *x, double *y)
{
    double c = cos((double)p->angle), s = sin((double)p->angle);
    double vx = (double)sh->vertices[i].x, vy = (double)sh->vertices[i].y;
    *x = (double)p->x + c * vx - s * vy;
    *y = (double)p->y + s * vx + c * vy;
}

/* Fit every body over every frame (or show o->view), y up, the longer
 * side o->size pixels. */
static view fit_view(const render_movie *m, const render_options *o)
{
    double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL;
    double w, h, margin, big;
    int f, b, i, size = o->size, note = m->note != NULL;
    view v;
    for (f = 0; f < m->frame_count && !o->fixed_view; ++f) {
        for (b = 0; b < m->body_count; ++b) {
            const render_shape *sh = &m->shapes[b];
            const render_pose *p = &m->poses[(size_t)f * (size_t)m->body_count + (size_t)b];
            if (sh->circle) {
                double r = (double)sh->radius, x = (double)p->x, y = (double)p->y;
                if (x - r < xmin) xmin = x - r;
                if (x + r > xmax) xmax = x + r;
                if (y - r < ymin) ymin = y - r;
                if (y + r > ymax) ymax = y + r;
            } else {
                for (i = 0; i < sh->vertex_count; ++i) {
                    double x, y;
                    world_vertex(sh, p, i, &x, &y);
                    if (x < xmin) xmin = x;
                    if (x > xmax) xmax = x;
                    if (y < ymin) ymin = y;
                    if (y > ymax) ymax = y;
                }
            }
        }
    }
    if (o->fixed_view) {
        xmin = o->view[0];
        ymin = o->view[1];
        xmax = o->view[2];
        ymax = o->view[3];
    } else if (!(xmin <= xmax)) { /* no bodies */
        xmin = ymin = -1.0;
        xmax = ymax = 1.0;
    }
    w = xmax - xmin;
    h = ymax - ymin;
    big = w > h ? w : h;
    if (!(big > 0.0))
        big = 1.0;
    margin = o->fixed_view ? 0.0 : MARGIN_SHARE * big;
    xmin -= margin; xmax += margin; ymin -= margin; ymax += margin;
    big += 2.0 * margin;
    v.s = (double)size / big;
    w = xmax - xmin;
    if (w * v.s < MIN_WIDTH_PX) { /* room for the time label */
        double grow = (MIN_WIDTH_PX / v.s - w) / 2.0;
        xmin -= grow;
        xmax += grow;
    }
    v.x0 = xmin;
    v.y1 = ymax;
    v.width = (int)ceil((xmax - xmin) * v.s);
    v.top = BAND_PX + (note ? NOTE_PX : 0);
    v.height = v.top + (int)ceil((ymax - ymin) * v.s);
    return v;
}

/* A number with one decimal, "12" rather than "12.0", "0" not "-0". */
static void put_num(FILE *f, double x)
{
    char buf[64];
    size_t n;
    snprintf(buf, sizeof buf, "%.1f", x);
    n = strlen(buf);
    if (n >= 2 && buf[n - 2] == '.' && buf[n - 1] == '0')
        buf[n -= 2] = '\0';
    if (strcmp(buf, "-0") == 0)
        strcpy(buf, "0");
    fputs(buf, f);
}

static void put_escaped(FILE *f, const char *s)
{
    for (; *s; ++s) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default:
            if ((unsigned char)*s < 0x20)
                fputc('?', f); /* not allowed in XML 1.0 */
            else
                fputc(*s, f);
        }
    }
}

double render_svg_estimate(long frames, int bodies, long impacts)
{
    /* per frame: a time label (~200 bytes) and a translate and a rotate
     * value per body (~22 bytes); per body ~400 bytes; per impact ~200 */
    return (double)frames * (200.0 + 22.0 * (double)bodies) +
           400.0 * (double)bodies + 200.0 * (double)impacts + 2000.0;
}

/* Frame timing: frame i starts at key(i) in [0, 1) of the loop; the last
 * frame is held one regular interval. Keys come from step numbers, so
 * evenly sampled runs get exactly even keys. */
typedef struct timing {
    double dur;     /* loop length, s (simulated = shown) */
    double span;    /* loop length in steps */
    int regular;    /* every interval equal: keyTimes can be left out */
} timing;

static timing frame_timing(const render_movie *m)
{
    timing tm;
    long first = m->steps[0], last = m->steps[m->frame_count - 1], every;
    double dt;
    int i;
    tm.regular = 1;
    if (m->frame_count < 2 || last <= first) {
        tm.dur = 0.0;
        tm.span = 1.0;
        return tm;
    }
    every = m->steps[1] - first;
    for (i = 1; i + 1 < m->frame_count; ++i)
        if (m->steps[i + 1] - m->steps[i] != every)
            tm.regular = 0;
    dt = (m->times[m->frame_count - 1] - m->times[0]) / (double)(last - first);
    tm.span = (double)(last - first + every);
    tm.dur = tm.span * dt;
    if (!(tm.dur > 0.0))
        tm.dur = tm.span; /* dt reported as 0: one step a second */
    return tm;
}

static double frame_key(const render_movie *m, const timing *tm, int i)
{
    return (double)(m->steps[i] - m->steps[0]) / tm->span;
}

static void put_key_times(FILE *f, const render_movie *m, const timing *tm)
{
    int i;
    if (tm->regular)
        return;
    fputs(" keyTimes=\"", f);
    for (i = 0; i < m->frame_count; ++i)
        fprintf(f, "%s%.6g", i ? ";" : "", frame_key(m, tm, i));
    fputc('"', f);
}

static void put_anim_head(FILE *f, const char *what, const timing *tm)
{
    fprintf(f, "<%s dur=\"%.6gs\" repeatCount=\"indefinite\" calcMode=\"discrete\"",
            what, tm->dur);
}

static double degrees(float angle)
{
    return -(double)angle * (180.0 / 3.14159265358979323846); /* y down */
}

static void put_body(FILE *f, const render_movie *m, const view *v,
                     const timing *tm, int b)
{
    const render_shape *sh = &m->shapes[b];
    const render_pose *p0 = &m->poses[b];
    int moves = 0, turns = 0, fr, i;
    const char *fill = sh->fixed ? STATIC_FILL : palette[(size_t)b % PALETTE_SIZE];
    const char *stroke = sh->fixed ? STATIC_STROKE : BODY_STROKE;
    for (fr = 1; fr < m->frame_count; ++fr) {
        const render_pose *p = &m->poses[(size_t)fr * (size_t)m->body_count + (size_t)b];
        if (p->x != p0->x || p->y != p0->y)
            moves = 1;
        if (p->angle != p0->angle)
            turns = 1;
    }
    fprintf(f, "<g id=\"body%d\" transform=\"translate(", b);
    put_num(f, px_x(v, (double)p0->x));
    fputc(',', f);
    put_num(f, px_y(v, (double)p0->y));
    fputs(")\">", f);
    if (moves) {
        fputs("\n", f);
        put_anim_head(f, "animateTransform attributeName=\"transform\" type=\"translate\"", tm);
        put_key_times(f, m, tm);
        fputs(" values=\"", f);
        for (fr = 0; fr < m->frame_count; ++fr) {
            const render_pose *p = &m->poses[(size_t)fr * (size_t)m->body_count + (size_t)b];
            if (fr)
                fputc(';', f);
            put_num(f, px_x(v, (double)p->x));
            fputc(',', f);
            put_num(f, px_y(v, (double)p->y));
        }
        fputs("\"/>\n", f);
    }
    fputs("<g transform=\"rotate(", f);
    put_num(f, degrees(p0->angle));
    fputs(")\">", f);
    if (turns) {
        fputs("\n", f);
        put_anim_head(f, "animateTransform attributeName=\"transform\" type=\"rotate\"", tm);
        put_key_times(f, m, tm);
        fputs(" values=\"", f);
        for (fr = 0; fr < m->frame_count; ++fr) {
            const render_pose *p = &m->poses[(size_t)fr * (size_t)m->body_count + (size_t)b];
            if (fr)
                fputc(';', f);
            put_num(f, degrees(p->angle));
        }
        fputs("\"/>\n", f);
    }
    if (sh->circle) {
        double r = (double)sh->radius * v->s;
        fputs("<circle r=\"", f);
        put_num(f, r < 0.5 ? 0.5 : r);
        fprintf(f, "\" fill=\"%s\" stroke=\"%s\"/>", fill, stroke);
        /* the body's x axis, to show its rotation */
        fputs("<line x1=\"0\" y1=\"0\" x2=\"", f);
        put_num(f, r);
        fprintf(f, "\" y2=\"0\" stroke=\"%s\"/>", stroke);
    } else {
        fputs("<polygon points=\"", f);
        for (i = 0; i < sh->vertex_count; ++i) {
            if (i)
                fputc(' ', f);
            put_num(f, (double)sh->vertices[i].x * v->s);
            fputc(',', f);
            put_num(f, -(double)sh->vertices[i].y * v->s);
        }
        fprintf(f, "\" fill=\"%s\" stroke=\"%s\"/>", fill, stroke);
    }
    fputs("</g></g>\n", f);
}

/* One element shown from key a to key b of the loop (discrete): a < 0
 * means from the start, b >= 1 until the end. */
static void put_window(FILE *f, const char *attr, const char *off,
                       const char *on, double a, double b, const timing *tm)
{
    fprintf(f, "<animate attributeName=\"%s\" dur=\"%.6gs\" "
               "repeatCount=\"indefinite\" calcMode=\"discrete\" ",
            attr, tm->dur);
    if (a <= 0.0 && b >= 1.0)
        fprintf(f, "values=\"%s\"", on);
    else if (a <= 0.0)
        fprintf(f, "values=\"%s;%s\" keyTimes=\"0;%.6g\"", on, off, b);
    else if (b >= 1.0)
        fprintf(f, "values=\"%s;%s\" keyTimes=\"0;%.6g\"", off, on, a);
    else
        fprintf(f, "values=\"%s;%s;%s\" keyTimes=\"0;%.6g;%.6g\"", off, on, off, a, b);
    fputs("/>", f);
}

static void frame_label(char *buf, size_t n, const render_movie *m, int i)
{
    snprintf(buf, n, "t = %.3f s  step %ld", m->times[i], m->steps[i]);
}

int render_svg(FILE *f, const render_movie *m, const render_options *o)
{
    view v = fit_view(m, o);
    timing tm = frame_timing(m);
    int animated = m->frame_count > 1;
    int b, i;
    char label[96];

    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
               "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" "
               "width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\">\n",
            v.width, v.height, v.width, v.height);
    fputs("<title>carom: ", f);
    put_escaped(f, m->title ? m->title : "");
    fputs("</title>\n", f);
    fputs("<desc>", f);
    put_escaped(f, m->generator ? m->generator : "carom");
    fprintf(f, " render: %d bodies, %d frames from step %ld to %ld, %.6g s "
               "looping, y up, %.6g px per m.</desc>\n",
            m->body_count, m->frame_count, m->steps[0],
            m->steps[m->frame_count - 1], tm.dur, v.s);
    fputs("<style>text{font-family:monospace;font-size:14px;fill:#222}"
          "circle,polygon,line{stroke-width:1}</style>\n", f);
    fprintf(f, "<rect width=\"%d\" height=\"%d\" fill=\"#ffffff\"/>\n", v.width,
            v.height);
    fprintf(f, "<clipPath id=\"view\"><rect x=\"0\" y=\"%d\" width=\"%d\" "
               "height=\"%d\"/></clipPath>\n", v.top, v.width, v.height - v.top);
    fputs("<g id=\"bodies\" clip-path=\"url(#view)\">\n", f);
    for (b = 0; b < m->body_count; ++b)
        put_body(f, m, &v, &tm, b);
    fputs("</g>\n", f);

    if (o->impacts && m->impact_count > 0) {
        double show = MARKER_SECONDS;
        if (animated && tm.dur / m->frame_count > show)
            show = tm.dur / m->frame_count; /* at least one frame */
        fputs("<g id=\"impacts\" clip-path=\"url(#view)\">\n", f);
        for (i = 0; i < m->impact_count; ++i) {
            const render_impact *im = &m->impacts[i];
            fputs("<circle class=\"impact\" cx=\"", f);
            put_num(f, px_x(&v, (double)im->x));
            fputs("\" cy=\"", f);
            put_num(f, px_y(&v, (double)im->y));
            fprintf(f, "\" r=\"%g\" fill=\"%s\" stroke=\"#ffffff\" opacity=\"0\">",
                    MARKER_PX, MARKER_FILL);
            if (animated) {
                double a = (im->t - m->times[0]) / tm.dur;
                put_window(f, "opacity", "0", "0.9", a, a + show / tm.dur, &tm);
            }
            fputs("</circle>\n", f);
        }
        fputs("</g>\n", f);
    }

    fputs("<g id=\"time\">\n", f);
    for (i = 0; i < m->frame_count; ++i) {
        frame_label(label, sizeof label, m, i);
        fprintf(f, "<text class=\"time\" x=\"8\" y=\"17\" visibility=\"%s\">%s",
                i == 0 ? "visible" : "hidden", label);
        if (animated)
            put_window(f, "visibility", "hidden", "visible",
                       i == 0 ? -1.0 : frame_key(m, &tm, i),
                       i + 1 < m->frame_count ? frame_key(m, &tm, i + 1) : 1.0, &tm);
        fputs("</text>\n", f);
    }
    fputs("</g>\n", f);
    if (m->note) {
        fprintf(f, "<text class=\"note\" x=\"8\" y=\"%d\" fill=\"#b00000\" "
                   "style=\"font-size:11px\">",
                BAND_PX + NOTE_PX - 6);
        put_escaped(f, m->note);
        fputs("</text>\n", f);
    }
    fputs("</svg>\n", f);
    return ferror(f) ? -1 : 0;
}

/* ---- PNG frames through gnuplot ------------------------------------------ */

int render_have_gnuplot(void)
{
    const char *path = getenv("PATH");
    char buf[4096];
    if (!path)
        path = "/usr/bin:/bin";
    while (*path) {
        const char *end = strchr(path, ':');
        size_t n = end ? (size_t)(end - path) : strlen(path);
        if (n + sizeof "/gnuplot" < sizeof buf) {
            if (n == 0)
                strcpy(buf, "./gnuplot");
            else {
                memcpy(buf, path, n);
                strcpy(buf + n, "/gnuplot");
            }
            if (access(buf, X_OK) == 0)
                return 1;
        }
        path += n;
        if (*path == ':')
            ++path;
    }
    return 0;
}

/* A gnuplot single-quoted string: '' stands for '. */
static void gp_quoted(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; ++s) {
        if (*s == '\'')
            fputc('\'', f);
        if ((unsigned char)*s >= 0x20)
            fputc(*s, f);
    }
    fputc('\'', f);
}

int render_png_dir(const char *dir, char *err, size_t errlen)
{
    struct stat sb;
    if (stat(dir, &sb) != 0) {
        if (mkdir(dir, 0777) != 0) {
            snprintf(err, errlen, "--png: cannot make directory '%s': %s", dir,
                     strerror(errno));
            return -1;
        }
    } else if (!S_ISDIR(sb.st_mode)) {
        snprintf(err, errlen, "--png: '%s' exists and is not a directory", dir);
        return -1;
    }
    return 0;
}

int render_png(const char *dir, const render_movie *m, const render_options *o,
               char *err, size_t errlen)
{
    view v = fit_view(m, o);
    struct stat sb;
    FILE *gp;
    int fr, b, i, status;
    size_t pathlen = strlen(dir) + 32;
    char *path, label[96];
    void (*old_pipe)(int);
    double show = MARKER_SECONDS, x1 = v.x0 + v.width / v.s;
    double y0 = v.y1 - (v.height - v.top) / v.s;

    if (render_png_dir(dir, err, errlen) != 0)
        return -1;
    if (!render_have_gnuplot()) {
        snprintf(err, errlen, "--png needs gnuplot, which is not on PATH "
                              "(Debian: apt-get install gnuplot-nox)");
        return -1;
    }
    path = (char *)malloc(pathlen);
    if (!path) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    fflush(NULL);
    gp = popen("gnuplot", "w");
    if (!gp) {
        snprintf(err, errlen, "cannot start gnuplot: %s", strerror(errno));
        free(path);
        return -1;
    }
    old_pipe = signal(SIGPIPE, SIG_IGN); /* gnuplot may die: report, don't crash */
    fprintf(gp, "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
                "  set terminal pngcairo size %d,%d background rgb 'white' font ',10'\n"
                "} else {\n"
                "  set terminal png size %d,%d background rgb 'white'\n"
                "}\n", v.width, v.height, v.width, v.height);
    fprintf(gp, "unset border\nunset tics\nunset key\n"
                "set lmargin at screen 0\nset rmargin at screen 1\n"
                "set bmargin at screen 0\nset tmargin at screen %.9g\n"
                "set xrange [%.9g:%.9g]\nset yrange [%.9g:%.9g]\n",
            1.0 - (double)v.top / v.height, v.x0, x1, y0, v.y1);
    if (m->note) {
        fprintf(gp, "set label 2 ");
        gp_quoted(gp, m->note);
        fprintf(gp, " at screen 0.01, screen %.9g left textcolor rgb '#b00000'\n",
                1.0 - (double)(BAND_PX + NOTE_PX - 6) / v.height);
    }
    if (m->frame_count > 1) {
        double h = (m->times[m->frame_count - 1] - m->times[0]) / (m->frame_count - 1);
        if (h > show)
            show = h;
    }
    for (fr = 0; fr < m->frame_count; ++fr) {
        int obj = 1, arrow = 1;
        snprintf(path, pathlen, "%s/frame-%05d.png", dir, fr);
        fputs("set output ", gp);
        gp_quoted(gp, path);
        fputs("\nunset object\nunset arrow\n", gp);
        frame_label(label, sizeof label, m, fr);
        fprintf(gp, "set label 1 '%s' at screen 0.01, screen %.9g left\n", label,
                1.0 - 17.0 / v.height);
        for (b = 0; b < m->body_count; ++b) {
            const render_shape *sh = &m->shapes[b];
            const render_pose *p = &m->poses[(size_t)fr * (size_t)m->body_count + (size_t)b];
            const char *fill = sh->fixed ? STATIC_FILL : palette[(size_t)b % PALETTE_SIZE];
            const char *stroke = sh->fixed ? STATIC_STROKE : BODY_STROKE;
            if (sh->circle) {
                double r = (double)sh->radius;
                fprintf(gp, "set object %d circle at %.9g,%.9g size %.9g fc rgb '%s' "
                            "fs solid 1.0 border lc rgb '%s' front\n",
                        obj++, (double)p->x, (double)p->y, r, fill, stroke);
                fprintf(gp, "set arrow %d from %.9g,%.9g to %.9g,%.9g nohead "
                            "lc rgb '%s' front\n", arrow++, (double)p->x, (double)p->y,
                        (double)p->x + r * cos((double)p->angle),
                        (double)p->y + r * sin((double)p->angle),
                        stroke);
            } else {
                double x, y;
                fprintf(gp, "set object %d polygon", obj++);
                for (i = 0; i <= sh->vertex_count; ++i) {
                    world_vertex(sh, p, i % sh->vertex_count, &x, &y);
                    fprintf(gp, " %s %.9g,%.9g", i ? "to" : "from", x, y);
                }
                fprintf(gp, " fc rgb '%s' fs solid 1.0 border lc rgb '%s' front\n",
                        fill, stroke);
            }
        }
        if (o->impacts) {
            for (i = 0; i < m->impact_count; ++i) {
                const render_impact *im = &m->impacts[i];
                if (im->t <= m->times[fr] && im->t > m->times[fr] - show)
                    fprintf(gp, "set object %d circle at %.9g,%.9g size %.9g "
                                "fc rgb '%s' fs solid 0.9 noborder front\n",
                            obj++, (double)im->x, (double)im->y, MARKER_PX / v.s,
                            MARKER_FILL);
            }
        }
        fputs("plot NaN notitle\n", gp);
    }
    fputs("unset output\nexit\n", gp);
    status = pclose(gp);
    signal(SIGPIPE, old_pipe);
    if (status != 0) {
        snprintf(err, errlen, "gnuplot failed (status %d)", status);
        free(path);
        return -1;
    }
    snprintf(path, pathlen, "%s/frame-%05d.png", dir, m->frame_count - 1);
    if (stat(path, &sb) != 0 || sb.st_size == 0) {
        snprintf(err, errlen, "gnuplot did not write %s", path);
        free(path);
        return -1;
    }
    free(path);
    return 0;
}

/* ---- impact points --------------------------------------------------------- */

/* The support feature of a shape along world direction d: one point
 * (n == 1) or a face (n == 2, its ends along the tangent). */
typedef struct feature {
    int n;
    double x[2], y[2];
} feature;

static feature support(const render_shape *sh, const render_pose *p, double dx,
                       double dy)
{
    feature ft;
    ft.n = 1;
    if (sh->circle) {
        ft.x[0] = (double)p->x + dx * (double)sh->radius;
        ft.y[0] = (double)p->y + dy * (double)sh->radius;
    } else {
        double best = -HUGE_VAL, size = 0.0, tol, tmin = HUGE_VAL, tmax = -HUGE_VAL;
        int i;
        for (i = 0; i < sh->vertex_count; ++i) {
            double x, y, r;
            world_vertex(sh, p, i, &x, &y);
            if (x * dx + y * dy > best)
                best = x * dx + y * dy;
            r = hypot((double)sh->vertices[i].x, (double)sh->vertices[i].y);
            if (r > size)
                size = r;
        }
        tol = 0.02 * size; /* a nearly flat face counts as a face */
        for (i = 0; i < sh->vertex_count; ++i) {
            double x, y, t;
            world_vertex(sh, p, i, &x, &y);
            if (x * dx + y * dy < best - tol)
                continue;
            t = -x * dy + y * dx; /* along the tangent (-dy, dx) */
            if (t < tmin) {
                tmin = t;
                ft.x[0] = x;
                ft.y[0] = y;
            }
            if (t > tmax) {
                tmax = t;
                ft.x[1] = x;
                ft.y[1] = y;
            }
        }
        if (tmax > tmin)
            ft.n = 2;
    }
    return ft;
}

carom_vec2 render_contact_point(const render_shape *a, const render_pose *pa,
                                const render_shape *b, const render_pose *pb,
                                carom_vec2 normal)
{
    double nx = (double)normal.x, ny = (double)normal.y;
    feature fa = support(a, pa, nx, ny), fb = support(b, pb, -nx, -ny);
    carom_vec2 out;
    if (fa.n == 1 && fb.n == 1) {
        out.x = (float)((fa.x[0] + fb.x[0]) / 2.0);
        out.y = (float)((fa.y[0] + fb.y[0]) / 2.0);
    } else if (fa.n == 1 || fb.n == 1) {
        const feature *pt = fa.n == 1 ? &fa : &fb;
        out.x = (float)pt->x[0];
        out.y = (float)pt->y[0];
    } else {
        /* two faces: the middle of their overlap along the tangent */
        double tx = -ny, ty = nx;
        double a0 = fa.x[0] * tx + fa.y[0] * ty, a1 = fa.x[1] * tx + fa.y[1] * ty;
        double b0 = fb.x[0] * tx + fb.y[0] * ty, b1 = fb.x[1] * tx + fb.y[1] * ty;
        double lo, hi, t, n;
        if (a0 > a1) { t = a0; a0 = a1; a1 = t; }
        if (b0 > b1) { t = b0; b0 = b1; b1 = t; }
        lo = a0 > b0 ? a0 : b0;
        hi = a1 < b1 ? a1 : b1;
        t = (lo + hi) / 2.0;
        n = (fa.x[0] * nx + fa.y[0] * ny + fa.x[1] * nx + fa.y[1] * ny +
             fb.x[0] * nx + fb.y[0] * ny + fb.x[1] * nx + fb.y[1] * ny) / 4.0;
        out.x = (float)(t * tx + n * nx);
        out.y = (float)(t * ty + n * ny);
    }
    return out;
}
