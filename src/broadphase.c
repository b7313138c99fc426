/*
 * broadphase.c -- candidate pairs by sort and sweep.
 *
 * Each body's bounding box (grown by a margin that covers the step's
 * motion) is sorted by its lower x bound; a sweep then tests each box only
 * against the boxes that start before it ends. Cost: O(n log n) for the
 * sort plus O(n + k) for the sweep with k overlapping x intervals, instead
 * of the n (n - 1) / 2 of all pairs.
 *
 * The sort is a bottom-up merge sort in caller storage: stable, so ties
 * keep body order and the result never depends on anything but the input.
 * Pairs come out sorted by (a, b), the order the solver visits them in.
 */
#include "internal.h"

/*
 * Bottom-up merge sort of n elements of TYPE in a, with scratch tmp of the
 * same size; stable: an element from the right run is taken only if it is
 * strictly LESS than the left one. Defined once, instantiated per type.
 */
#define CR_DEFINE_MERGE_SORT(NAME, TYPE, LESS)                                \
    static void NAME(TYPE *a, TYPE *tmp, int n)                               \
    {                                                                         \
        int width, i;                                                         \
        TYPE *src = a, *dst = tmp, *swap;                                     \
        for (width = 1; width < n; width *= 2) {                              \
            for (i = 0; i < n; i += 2 * width) {                              \
                int mid = i + width < n ? i + width : n;                      \
                int hi = i + 2 * width < n ? i + 2 * width : n;               \
                int l = i, r = mid, k = i;                                    \
                while (l < mid && r < hi)                                     \
                    dst[k++] = LESS(src[r], src[l]) ? src[r++] : src[l++];    \
                while (l < mid)                                               \
                    dst[k++] = src[l++];                                      \
                while (r < hi)                                                \
                    dst[k++] = src[r++];                                      \
            }                                                                 \
            swap = src;                                                       \
            src = dst;                                                        \
            dst = swap;                                                       \
        }                                                                     \
        if (src != a)                                                         \
            for (i = 0; i < n; ++i)                                           \
                a[i] = src[i];                                                \
    }

/* proxies by lower x bound (a counted float compare) */
#define CR_PROXY_LESS(x, y) cr_lt((x).lo_x, (y).lo_x)
/* pairs by (a, b) */
#define CR_PAIR_LESS(x, y) ((x).a < (y).a || ((x).a == (y).a && (x).b < (y).b))

CR_DEFINE_MERGE_SORT(cr_sort_proxies, cr_proxy, CR_PROXY_LESS)
CR_DEFINE_MERGE_SORT(cr_sort_pairs, cr_pair, CR_PAIR_LESS)

/* Pairs of the boxes already in w->proxies (one per body, any order);
 * returns the number found (stored ones plus dropped ones). */
int cr_broadphase_pairs(carom_world *w)
{
    int i, j, n = w->body_count, found = 0;
    int cap = w->def.max_pairs;

    cr_sort_proxies(w->proxies, w->proxy_tmp, n);

    w->pair_count = 0;
    for (i = 0; i < n; ++i) {
        const cr_proxy *p = &w->proxies[i];
        for (j = i + 1; j < n && cr_le(w->proxies[j].lo_x, p->hi_x); ++j) {
            const cr_proxy *q = &w->proxies[j];
            int a = p->body, b = q->body;
            if (w->bodies[a].type == CAROM_BODY_STATIC &&
                w->bodies[b].type == CAROM_BODY_STATIC)
                continue;
            if (cr_lt(q->hi_y, p->lo_y) || cr_lt(p->hi_y, q->lo_y))
                continue;
            ++found;
            if (w->pair_count < cap) {
                cr_pair pr;
                pr.a = a < b ? a : b;
                pr.b = a < b ? b : a;
                w->pairs[w->pair_count++] = pr;
            }
        }
    }
    w->pairs_dropped = found - w->pair_count;
    cr_sort_pairs(w->pairs, w->pair_tmp, w->pair_count);
    return found;
}

/* Pairs of the bodies' current boxes grown by margin. */
int cr_broadphase(carom_world *w, float margin)
{
    int i;
    for (i = 0; i < w->body_count; ++i) {
        cr_body_bounds(&w->bodies[i], margin, &w->proxies[i]);
        w->proxies[i].body = i;
    }
    return cr_broadphase_pairs(w);
}
