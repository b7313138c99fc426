/*
 * broadphase.c -- candidate pairs from a uniform grid, rebuilt each step
 * (or, for few bodies, a sweep).
 *
 * The cell is twice the mean box size of the bodies (leaving out boxes
 * more than CR_BIG_FACTOR times the mean: walls), or the largest of them
 * if that is smaller; a body whose box fits
 * in a cell is filed under the cell of its box centre, so two such boxes
 * that overlap have centres in the same or adjacent cells: each cell is
 * compared with itself and its four "forward" neighbours (right, and the
 * three above), which finds every pair exactly once. Cells map into a
 * power-of-two table (a patch of cells that tiles the plane, so that
 * neighbouring cells are neighbours in memory) filled by a counting sort,
 * so the grid needs no allocation and no per-cell storage; items keep
 * their cell coordinates, so two cells that share a bucket are told apart.
 * Boxes larger than a cell
 * ("big": walls, floors, long rods) are tested against the items of the
 * buckets their box covers (widened by two cells: cr_big_pairs).
 *
 * Cost: O(n) to build and O(n + pairs) to query, for any layout; the sort
 * of pairs by (a, b) is two counting passes over body slots, also linear.
 * Everything is deterministic: the same boxes give the same pairs in the
 * same order.
 *
 * Up to sweep_max bodies (CR_SWEEP_MAX in a world) the grid is not
 * filled: the boxes are swept along one axis (cr_sweep_build), which
 * costs less for a hundred bodies; the same pairs.
 *
 * With CAROM_ENABLE_GRID off every box is tested against every other
 * instead: the same pairs, in the same (a, b) order, with less code and
 * no grid arrays, for small worlds.
 */
#include "broadphase.h"

/* Cell coordinates are clamped here, so a huge coordinate over a tiny cell
 * cannot overflow an int (clamped cells only cost extra candidates). */
#define CR_CELL_LIMIT 1.0e9f
/* Boxes larger than this many times the mean box do not set the cell. */
#ifndef CR_BIG_FACTOR
#define CR_BIG_FACTOR 4.0f
#endif

typedef struct cr_pair_out {
    cr_pair *out;
    int cap;
    long found;
    cr_pair_accept_fn accept;
    void *ctx;
} cr_pair_out;

/* Pair (a, b), whose boxes overlap, if the filter accepts it. */
static void cr_emit(cr_pair_out *o, int a, int b)
{
    cr_pair *p;
    /* past the capacity the count stops at cap + 1: it cannot overflow,
     * whatever the number of overlapping bodies */
    if (o->found > (long)o->cap || a == b || !o->accept(o->ctx, a, b))
        return;
    if (o->found++ >= (long)o->cap)
        return;
    p = &o->out[o->found - 1];
    cr_pair_init(p, a < b ? a : b, a < b ? b : a);
}

#if CAROM_ENABLE_GRID

int cr_broadphase_bucket_cap(int capacity)
{
    int n = 16;
    while (n < 2 * capacity)
        n *= 2;
    return n;
}

/* floor(v), clamped, without libm */
static int cr_cell_of(float v)
{
    int i;
    v = cr_clamp(v, cr_neg(CR_CELL_LIMIT), CR_CELL_LIMIT);
    i = (int)v;
    /* (truncation rounds a negative v up: one less; without a branch,
     * which the signs of a layout around 0 mispredict half the time) */
    return i - cr_lt(v, (float)i);
}

/* The bucket of cell (cx, cy): the table is a 2^xbits by 2^ybits patch of
 * cells that tiles the plane (cell coordinates modulo its sides), so
 * neighbouring cells have neighbouring buckets: a cell's forward
 * neighbours are one bucket and one row of buckets further on, and
 * finding pairs walks the items almost in memory order (a scattering hash
 * made this loop wait on memory: 38 % of a 10^4-body gas step). */
static int cr_bucket(const cr_broadphase *bp, int cx, int cy)
{
    return (int)(((unsigned)cx & bp->xmask) | (((unsigned)cy & bp->ymask) << bp->xbits));
}

/*
 * Few bodies (sweep_max or fewer, CR_SWEEP_MAX in a world): no grid, a
 * sweep along one axis.
 * The proxies are the bodies in slot order (queries test them in that
 * order, as the build without the grid does). The sweep's copies (tmp,
 * free until the pairs are found) are sorted by the lower end of their
 * box along the axis, by insertion from the last step's order
 * (start[0..order_n), body slots), which motion changes a little: nearly
 * linear. The axis is the one along which the box centres spread
 * further (a tower is swept along y, a row along x), changed only when
 * the other spreads half as far again; along y the copies hold their
 * boxes with x and y swapped, so one sweep serves both. For a hundred
 * bodies this costs less than a grid's counting sort, cells and forward
 * neighbours: a 100-body elastic gas step 72.6 -> 65.9 k instructions,
 * the same pairs.
 */
static void cr_sweep_copy(cr_proxy *to, const cr_proxy *from, int axis)
{
    *to = *from;
    if (axis) {
        to->box.lo_x = from->box.lo_y;
        to->box.lo_y = from->box.lo_x;
        to->box.hi_x = from->box.hi_y;
        to->box.hi_y = from->box.hi_x;
    }
}

static void cr_sweep_build(cr_broadphase *bp, const cr_box *boxes, const int *bodies, int n)
{
    int *order = bp->start, *at = bp->count;
    cr_proxy *px = bp->proxies, *sx = bp->tmp;
    int i, m = 0, top = n > 0 ? bodies[n - 1] : -1, axis = bp->sweep_axis;
    float x0 = 0.0f, x1 = 0.0f, y0 = 0.0f, y1 = 0.0f;
    /* at[slot]: the slot's proxy, -1 if none, -2 once in sx */
    for (i = 0; i <= top; ++i)
        at[i] = -1;
    for (i = 0; i < n; ++i) {
        const cr_box *b = &boxes[bodies[i]];
        /* (twice the centre: the spread is compared, not measured) */
        float cx = cr_add(b->lo_x, b->hi_x), cy = cr_add(b->lo_y, b->hi_y);
        px[i].box = *b;
        px[i].body = bodies[i];
        px[i].cx = px[i].cy = 0;
        at[bodies[i]] = i;
        x0 = i ? cr_min(x0, cx) : cx;
        x1 = i ? cr_max(x1, cx) : cx;
        y0 = i ? cr_min(y0, cy) : cy;
        y1 = i ? cr_max(y1, cy) : cy;
    }
    {
        float sx_ = cr_sub(x1, x0), sy_ = cr_sub(y1, y0);
        int want = axis ? !cr_gt(sx_, cr_mul(1.5f, sy_)) : cr_gt(sy_, cr_mul(1.5f, sx_));
        if (want != axis || !bp->sweep) {
            axis = want;
            bp->order_n = 0; /* sorted along the other axis: from scratch */
        }
    }
    for (i = 0; i < bp->order_n; ++i) {
        int b = order[i];
        if (b <= top && at[b] >= 0) {
            cr_sweep_copy(&sx[m++], &px[at[b]], axis);
            at[b] = -2;
        }
    }
    for (i = 0; i < n; ++i)
        if (at[bodies[i]] >= 0)
            cr_sweep_copy(&sx[m++], &px[i], axis);
    for (i = 1; i < n; ++i)
        if (cr_lt(sx[i].box.lo_x, sx[i - 1].box.lo_x)) {
            cr_proxy p = sx[i];
            int j = i;
            do {
                sx[j] = sx[j - 1];
                --j;
            } while (j > 0 && cr_lt(p.box.lo_x, sx[j - 1].box.lo_x));
            sx[j] = p;
        }
    for (i = 0; i < n; ++i)
        order[i] = sx[i].body;
    bp->order_n = n;
    bp->sweep = 1;
    bp->sweep_axis = axis;
    bp->cell = bp->inv_cell = 1.0f; /* (no grid) */
    bp->grid_count = n;
    bp->big_count = 0;
}

/* Pairs of the sweep: each box against those after it along the axis
 * until one starts past its end (those start after it, so only the other
 * axis is left to test). */
static long cr_sweep_pairs(const cr_broadphase *bp, cr_pair_out *o)
{
    const cr_proxy *px = bp->tmp;
    int n = bp->grid_count, i, j;
    for (i = 0; i < n; ++i) {
        const cr_proxy *p = &px[i];
        float hi = p->box.hi_x, lo_y = p->box.lo_y, hi_y = p->box.hi_y;
        for (j = i + 1; j < n; ++j) {
            const cr_proxy *q = &px[j];
            if (cr_lt(hi, q->box.lo_x))
                break;
            if (!(cr_lt(q->box.hi_y, lo_y) | cr_lt(hi_y, q->box.lo_y)))
                cr_emit(o, p->body, q->body);
        }
    }
    return o->found;
}

void cr_broadphase_build(cr_broadphase *bp, const cr_box *boxes,
                         const int *bodies, int n)
{
    /* (locals: the stores into the int arrays below could otherwise be
     * stores into *bp, and every field would be read again) */
    cr_proxy *tmp = bp->tmp, *proxies = bp->proxies;
    int *start = bp->start, *key = bp->count;
    int i, grid = 0, big = 0, n_mean = n, buckets, xbits, bits = 0;
    unsigned xmask, ymask;
    float sum = 0.0f, largest = 0.0f, cell, inv_cell;

    if (n <= bp->sweep_max) {
        cr_sweep_build(bp, boxes, bodies, n);
        return;
    }
    bp->sweep = 0;
    bp->order_n = 0;
    /* the cell: twice the mean box size (largest side) of the bodies
     * that are not big: a mean over all, then over those within
     * CR_BIG_FACTOR of it, so a few walls do not coarsen the grid of
     * many small bodies. The first pass copies the items to tmp, in body
     * order: the passes after it read one array; each item's size waits
     * for them in the proxy it may later be sorted to (proxies[i].box.lo_x,
     * free until the scatter). */
    for (i = 0; i < n; ++i) {
        cr_proxy *p = &tmp[i];
        const cr_box *b = &p->box;
        float size;
        p->box = boxes[bodies[i]];
        p->body = bodies[i];
        size = cr_max(cr_sub(b->hi_x, b->lo_x), cr_sub(b->hi_y, b->lo_y));
        proxies[i].box.lo_x = size;
        sum = cr_add(sum, size);
    }
    if (n > 0) {
        float limit = cr_mul(CR_BIG_FACTOR, cr_div(sum, (float)n)), small = 0.0f;
        int count = 0;
        for (i = 0; i < n; ++i) {
            float size = proxies[i].box.lo_x;
            if (!cr_gt(size, limit)) {
                small = cr_add(small, size);
                largest = cr_max(largest, size);
                ++count;
            }
        }
        if (count > 0) {
            sum = small;
            n_mean = count;
        }
    }
    cell = n > 0 ? cr_mul(2.0f, cr_div(sum, (float)n_mean)) : 1.0f;
    /* bodies of about one size: a cell as large as the largest of them
     * (every one still fits, so the big items are the same) holds fewer
     * neighbours to test than twice their mean, up to 4 times fewer.
     * Instructions of a step: pile of 10^3 -1.8 to -2.3 %, gas of 10^4
     * -3.3 %; the same pairs in the same order */
    if (cr_gt(largest, 0.0f) && cr_lt(largest, cell))
        cell = largest;
    if (!cr_gt(cell, 0.0f) || !cr_finite(cell))
        cell = 1.0f;
    inv_cell = cr_div(1.0f, cell);
    bp->cell = cell;
    bp->inv_cell = inv_cell;
    bp->buckets = buckets = cr_broadphase_bucket_cap(n);
    while ((1 << bits) < buckets)
        ++bits;
    bp->xbits = xbits = (bits + 1) / 2;
    bp->xmask = xmask = (1u << xbits) - 1u;
    bp->ymask = ymask = (1u << (bits - xbits)) - 1u;

    /* grid items counted per bucket (key: their bucket, -1 for big) */
    for (i = 0; i < buckets; ++i)
        start[i] = 0;
    for (i = 0; i < n; ++i) {
        cr_proxy *p = &tmp[i];
        const cr_box *b = &p->box;
        /* big: a side longer than the cell, that is (boxes are finite)
         * its size, the longer side */
        if (cr_gt(proxies[i].box.lo_x, cell)) {
            p->cx = p->cy = 0;
            key[i] = -1;
            ++big;
            continue;
        }
        {
            int cx = cr_cell_of(cr_mul(cr_mul(0.5f, cr_add(b->lo_x, b->hi_x)), inv_cell));
            int cy = cr_cell_of(cr_mul(cr_mul(0.5f, cr_add(b->lo_y, b->hi_y)), inv_cell));
            int k = (int)(((unsigned)cx & xmask) | (((unsigned)cy & ymask) << xbits));
            p->cx = cx;
            p->cy = cy;
            key[i] = k;
            ++start[k];
        }
    }
    grid = n - big;
    /* end of each bucket, then filled backwards (stable: each bucket in
     * body order), which leaves the start of each; big items go after
     * the grid's, also in body order. (buckets is a power of two, 16 or
     * more: the running sum four at a time) */
    {
        int run = 0;
        for (i = 0; i < buckets; i += 4) {
            start[i] = run += start[i];
            start[i + 1] = run += start[i + 1];
            start[i + 2] = run += start[i + 2];
            start[i + 3] = run += start[i + 3];
        }
    }
    start[buckets] = grid;
    for (i = n - 1, big = n; i >= 0; --i) {
        if (key[i] < 0)
            proxies[--big] = tmp[i];
        else
            proxies[--start[key[i]]] = tmp[i];
    }
    bp->grid_count = grid;
    bp->big_count = n - grid;
}

/* Pairs of item p with the items of cell (cx, cy). */
CR_INLINE void cr_cell_pairs(const cr_broadphase *bp, const cr_proxy *p, int cx, int cy,
                             cr_pair_out *o)
{
    int k = cr_bucket(bp, cx, cy), j;
    for (j = bp->start[k]; j < bp->start[k + 1]; ++j) {
        const cr_proxy *q = &bp->proxies[j];
        if (q->cx == cx && q->cy == cy && cr_boxes_overlap(&p->box, &q->box))
            cr_emit(o, p->body, q->body);
    }
}

/* The table's columns (or rows) of cells v0..v1 (v0 <= v1; mask: the
 * table's side less one), in table order: the inclusive segment
 * seg[0..1], and seg[2..3] where they wrap (returns 4, else 2); every
 * column when the cells are as many as the table's. */
static int cr_segments(int v0, int v1, unsigned mask, unsigned seg[4])
{
    unsigned a = (unsigned)v0 & mask, b = (unsigned)v1 & mask;
    seg[0] = 0u;
    seg[1] = mask;
    if ((long)v1 - v0 >= (long)mask)
        return 2;
    if (a <= b) {
        seg[0] = a;
        seg[1] = b;
        return 2;
    }
    seg[1] = b;
    seg[2] = a;
    seg[3] = mask;
    return 4;
}

/* Pairs of big item p with the grid items whose box may overlap it. An
 * item that fits a cell (fl(hi - lo) <= cell, so hi - lo < 2 cells) and
 * overlaps p has lo > p.lo - 2 cells and hi < p.hi + 2 cells, and its
 * centre (between lo and hi, rounded or not) is filed under a cell of the
 * ranges below (rounding and the floor are monotone): the buckets of
 * those cells hold every such item. Each bucket is read once, in table
 * order, so the pairs are those of a test against every item, in the
 * same order. Measured on a 100-body gas in its four walls: 400 box tests
 * a step -> 141 (the items near a wall, and those of the cells that share
 * their buckets). */
static void cr_big_pairs(const cr_broadphase *bp, const cr_proxy *p, cr_pair_out *o)
{
    const cr_proxy *px = bp->proxies;
    const int *start = bp->start;
    const cr_box *q = &p->box;
    float reach = cr_mul(2.0f, bp->cell);
    int x0 = cr_cell_of(cr_mul(cr_sub(q->lo_x, reach), bp->inv_cell));
    int x1 = cr_cell_of(cr_mul(cr_add(q->hi_x, reach), bp->inv_cell));
    int y0 = cr_cell_of(cr_mul(cr_sub(q->lo_y, reach), bp->inv_cell));
    int y1 = cr_cell_of(cr_mul(cr_add(q->hi_y, reach), bp->inv_cell));
    int xbits = bp->xbits, nc, nr, a, c, j;
    unsigned cs[4], rs[4], r;
    nc = cr_segments(x0, x1, bp->xmask, cs);
    nr = cr_segments(y0, y1, bp->ymask, rs);
    for (a = 0; a < nr; a += 2) {
        if (nc == 2 && cs[0] == 0u && cs[1] == bp->xmask) {
            /* whole rows: the segment's buckets are one run */
            int end = start[(rs[a + 1] + 1u) << xbits];
            for (j = start[rs[a] << xbits]; j < end; ++j)
                if (cr_boxes_overlap(q, &px[j].box))
                    cr_emit(o, p->body, px[j].body);
            continue;
        }
        for (r = rs[a]; r <= rs[a + 1]; ++r)
            for (c = 0; c < nc; c += 2) {
                int end = start[(cs[c + 1] | (r << xbits)) + 1u];
                for (j = start[cs[c] | (r << xbits)]; j < end; ++j)
                    if (cr_boxes_overlap(q, &px[j].box))
                        cr_emit(o, p->body, px[j].body);
            }
    }
}

long cr_broadphase_pairs(const cr_broadphase *bp, const cr_box *boxes,
                         cr_pair_accept_fn accept, void *ctx, cr_pair *out,
                         int cap)
{
    /* (locals: cr_emit's stores could otherwise be stores into *bp) */
    const cr_proxy *px = bp->proxies;
    const int *start = bp->start;
    const unsigned xmask = bp->xmask, ymask = bp->ymask;
    const int xbits = bp->xbits, grid = bp->grid_count, n = grid + bp->big_count;
    cr_pair_out o;
    int i, j;
    (void)boxes; /* the proxies carry copies, read in one array */
    o.out = out;
    o.cap = cap;
    o.found = 0;
    o.accept = accept;
    o.ctx = ctx;
    if (bp->sweep)
        return cr_sweep_pairs(bp, &o);
    for (i = 0; i < grid; ++i) {
        const cr_proxy *p = &px[i];
        int cx = p->cx, cy = p->cy, end;
        unsigned col = (unsigned)cx & xmask;
        int k = (int)(col | (((unsigned)cy & ymask) << xbits));
        int k1 = (int)(col | ((((unsigned)cy + 1u) & ymask) << xbits));
        /* Neighbouring cells of a row are neighbouring buckets, so their
         * items are one run of proxies (unless the table wraps there):
         * each run is read once, its items told apart by their cells.
         * The table is at least 4 buckets wide and high (16 buckets or
         * more), so the cells of a run never share a bucket. */
        if (col < xmask) {
            /* the same cell (later items of the bucket only) and the
             * cell to the right: the rest of bucket k and bucket k + 1 */
            end = start[k + 2];
            for (j = i + 1; j < end; ++j) {
                const cr_proxy *q = &px[j];
                if ((q->cy == cy) & ((q->cx == cx) | (q->cx == cx + 1)) &
                    cr_boxes_overlap_flat(&p->box, &q->box))
                    cr_emit(&o, p->body, q->body);
            }
        } else {
            for (j = i + 1; j < start[k + 1]; ++j) {
                const cr_proxy *q = &px[j];
                if (q->cx == cx && q->cy == cy && cr_boxes_overlap(&p->box, &q->box))
                    cr_emit(&o, p->body, q->body);
            }
            cr_cell_pairs(bp, p, cx + 1, cy, &o);
        }
        if (col > 0u && col < xmask) {
            /* the three cells above: buckets k1 - 1 .. k1 + 1 */
            end = start[k1 + 2];
            for (j = start[k1 - 1]; j < end; ++j) {
                const cr_proxy *q = &px[j];
                if ((q->cy == cy + 1) & (q->cx >= cx - 1) & (q->cx <= cx + 1) &
                    cr_boxes_overlap_flat(&p->box, &q->box))
                    cr_emit(&o, p->body, q->body);
            }
        } else {
            cr_cell_pairs(bp, p, cx - 1, cy + 1, &o);
            cr_cell_pairs(bp, p, cx, cy + 1, &o);
            cr_cell_pairs(bp, p, cx + 1, cy + 1, &o);
        }
    }
    /* big boxes: against each other, then against the grid */
    for (i = grid; i < n; ++i) {
        const cr_proxy *p = &px[i];
        for (j = i + 1; j < n; ++j)
            if (cr_boxes_overlap(&p->box, &px[j].box))
                cr_emit(&o, p->body, px[j].body);
    }
    for (i = grid; i < n; ++i)
        cr_big_pairs(bp, &px[i], &o);
    return o.found;
}

int cr_broadphase_query(const cr_broadphase *bp, const cr_box *boxes,
                        const cr_box *q, cr_query_fn fn, void *ctx)
{
    int i, n = bp->grid_count + bp->big_count;
    /* grid items may reach half a cell beyond their centre's cell */
    float half = cr_mul(0.5f, bp->cell);
    int x0 = cr_cell_of(cr_mul(cr_sub(q->lo_x, half), bp->inv_cell));
    int x1 = cr_cell_of(cr_mul(cr_add(q->hi_x, half), bp->inv_cell));
    int y0 = cr_cell_of(cr_mul(cr_sub(q->lo_y, half), bp->inv_cell));
    int y1 = cr_cell_of(cr_mul(cr_add(q->hi_y, half), bp->inv_cell));
    long cells = ((long)x1 - x0 + 1) * ((long)y1 - y0 + 1);
    /* the sweep's proxies (no grid): every one, in slot order, as without
     * the grid */
    if (bp->sweep || cells > (long)bp->grid_count) {
        for (i = 0; i < bp->grid_count; ++i)
            if (cr_boxes_overlap(q, &boxes[bp->proxies[i].body]) &&
                !fn(ctx, bp->proxies[i].body))
                return 0;
    } else {
        int cx, cy;
        for (cy = y0; cy <= y1; ++cy)
            for (cx = x0; cx <= x1; ++cx) {
                int k = cr_bucket(bp, cx, cy), j;
                for (j = bp->start[k]; j < bp->start[k + 1]; ++j) {
                    const cr_proxy *p = &bp->proxies[j];
                    if (p->cx == cx && p->cy == cy &&
                        cr_boxes_overlap(q, &boxes[p->body]) && !fn(ctx, p->body))
                        return 0;
                }
            }
    }
    for (i = bp->grid_count; i < n; ++i)
        if (cr_boxes_overlap(q, &boxes[bp->proxies[i].body]) &&
            !fn(ctx, bp->proxies[i].body))
            return 0;
    return 1;
}


#else /* !CAROM_ENABLE_GRID: every box against every other */

int cr_broadphase_bucket_cap(int capacity)
{
    (void)capacity;
    return 0;
}

void cr_broadphase_build(cr_broadphase *bp, const cr_box *boxes,
                         const int *bodies, int n)
{
    int i;
    for (i = 0; i < n; ++i) {
        bp->proxies[i].box = boxes[bodies[i]];
        bp->proxies[i].body = bodies[i];
        bp->proxies[i].cx = bp->proxies[i].cy = 0;
    }
    bp->grid_count = n;
    bp->big_count = 0;
}

/* Bodies come in increasing slots, so the pairs come sorted by (a, b):
 * the order the grid's pairs have after cr_pairs_sort. */
long cr_broadphase_pairs(const cr_broadphase *bp, const cr_box *boxes,
                         cr_pair_accept_fn accept, void *ctx, cr_pair *out,
                         int cap)
{
    cr_pair_out o;
    int i, j;
    (void)boxes;
    o.out = out;
    o.cap = cap;
    o.found = 0;
    o.accept = accept;
    o.ctx = ctx;
    for (i = 0; i < bp->grid_count; ++i)
        for (j = i + 1; j < bp->grid_count; ++j)
            if (cr_boxes_overlap(&bp->proxies[i].box, &bp->proxies[j].box))
                cr_emit(&o, bp->proxies[i].body, bp->proxies[j].body);
    return o.found;
}

int cr_broadphase_query(const cr_broadphase *bp, const cr_box *boxes,
                        const cr_box *q, cr_query_fn fn, void *ctx)
{
    int i;
    for (i = 0; i < bp->grid_count; ++i)
        if (cr_boxes_overlap(q, &boxes[bp->proxies[i].body]) &&
            !fn(ctx, bp->proxies[i].body))
            return 0;
    return 1;
}

#endif /* CAROM_ENABLE_GRID */

#if CAROM_ENABLE_GRID
void cr_pairs_sort(cr_pair *pairs, cr_pair *tmp, int n, int *count, int slots)
{
    int i;
    if ((long)n * n <= 2L * slots) {
        /* few pairs for the slots (a gas: 9 pairs of 104 bodies): an
         * insertion sort, the same order (pairs are distinct) without the
         * four passes over every slot */
        for (i = 1; i < n; ++i) {
            cr_pair p = pairs[i];
            int j = i;
            while (j > 0 && (pairs[j - 1].a > p.a ||
                             (pairs[j - 1].a == p.a && pairs[j - 1].b > p.b))) {
                pairs[j] = pairs[j - 1];
                --j;
            }
            pairs[j] = p;
        }
        return;
    }
    /* by b into tmp, then stably by a back into pairs */
    for (i = 0; i <= slots; ++i)
        count[i] = 0;
    for (i = 0; i < n; ++i)
        ++count[pairs[i].b + 1];
    for (i = 0; i < slots; ++i)
        count[i + 1] += count[i];
    for (i = 0; i < n; ++i)
        tmp[count[pairs[i].b]++] = pairs[i];
    for (i = 0; i <= slots; ++i)
        count[i] = 0;
    for (i = 0; i < n; ++i)
        ++count[tmp[i].a + 1];
    for (i = 0; i < slots; ++i)
        count[i + 1] += count[i];
    for (i = 0; i < n; ++i)
        pairs[count[tmp[i].a]++] = tmp[i];
}
#endif
