// cxx_header.cpp -- carom.h and carom_config.h compile as C++ (make
// check-cxx: g++ -fsyntax-only -Wall -Wextra -Werror -pedantic, C++98 and
// C++17). Uses a little of every section so that the declarations are
// read as C++ declarations with C linkage.
#include "carom.h"
#include "carom_config.h"

extern "C" int cxx_uses_carom(void);

static void force(void *, int, const carom_body_state *, carom_vec2 *f, float *t)
{
    f->x = 0.0f;
    f->y = 0.0f;
    *t = 0.0f;
}

int cxx_uses_carom(void)
{
    carom_world_def wd = carom_default_world_def();
    carom_body_def bd = carom_default_body_def();
    carom_rot r = carom_rot_from_angle(0.5f);
    carom_profile prof;
    carom_op_weights wt;
    carom_status st = carom_body_def_set_box(&bd, 1.0f, 2.0f);
    wd.force_fn = force;
    carom_profile_reset(&prof);
    carom_op_weights_preset("seed", &wt);
    return (int)carom_world_buffer_size(&wd) + (int)st + (int)carom_rot_angle(r) +
           CAROM_VERSION_MAJOR + (carom_version()[0] == '0') +
           (int)carom_profile_cost(&prof, &wt, CAROM_PHASE_COUNT) +
           (int)(carom_status_string(CAROM_OK)[0]);
}
