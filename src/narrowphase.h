/*
 * narrowphase.h -- contact manifolds and separation bounds of shape pairs
 * (internal).
 */
#ifndef CAROM_NARROWPHASE_H
#define CAROM_NARROWPHASE_H

#include "body.h"
#include "contact.h"

/*
 * Manifold of shape A at pose (xa, qa) and shape B at (xb, qb): the normal
 * from A to B and the points whose separation is at most `reach` (> 0:
 * speculative points, kept before the shapes touch). `face_tol`: polygon
 * faces whose separations differ by less are equal, and A's is kept.
 * Returns the number of points (0: farther apart than reach).
 * Computed in A's frame, so the result depends on the relative pose only,
 * not on where in the world the pair sits.
 */
int cr_collide(const cr_shape *A, cr_v2 xa, cr_rot qa, const cr_shape *B,
               cr_v2 xb, cr_rot qb, float reach, float face_tol, float corner,
               cr_manifold *m);

/*
 * A lower bound of the distance between the two shapes (negative: they
 * overlap), for conservative advancement: exact for pairs with a circle;
 * for two polygons the separating-axis separation, which equals the
 * distance when the closest features are a vertex and an edge and is never
 * more than it.
 */
float cr_separation(const cr_shape *A, cr_v2 xa, cr_rot qa, const cr_shape *B,
                    cr_v2 xb, cr_rot qb);

#endif /* CAROM_NARROWPHASE_H */
