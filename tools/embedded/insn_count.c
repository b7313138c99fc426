/*
 * insn_count.c -- a QEMU TCG plugin (plugin API version 1, QEMU 4.2 to 8.x)
 * that counts the guest instructions executed and writes the running count
 * each time the guest executes the instruction at a marker address.
 *
 *   qemu-system-arm ... -plugin FILE.so,mark=0xADDR,out=PATH
 *       [,phase=0xA0:0xA1:...:0xA7][,meta=0xSTART:0xEND]
 *
 * With phase=, the count is also split into buckets: executing the
 * instruction at address Ak makes bucket k current (the phase firmware's
 * marker functions, fw_main.c), and each executed translation block adds
 * its instructions to the current bucket, or to the last bucket ("meta")
 * if it starts inside one of the meta= ranges (the measurement code
 * itself; meta= may be given more than once). Each mark then also prints
 * the buckets: "insn-buckets B0 B1 ... B7 META".
 *
 * The firmware calls platform_mark() (fw_main.c) before and after each
 * run's steps; the difference of two consecutive counts is the number of
 * instructions those steps executed. Written for this project: it declares
 * the few entry points of QEMU's plugin interface that it uses, so it
 * needs no QEMU headers (Debian's qemu packages ship none).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the part of QEMU's plugin interface used here (API version 1) ------ */
typedef uint64_t qemu_plugin_id_t;
struct qemu_info_t; /* not looked at */
struct qemu_plugin_tb;
struct qemu_plugin_insn;
enum qemu_plugin_cb_flags { QEMU_PLUGIN_CB_NO_REGS };
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 };
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu, void *udata);
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *udata);
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id,
                                               struct qemu_plugin_tb *tb);
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id,
                                           qemu_plugin_vcpu_tb_trans_cb_t cb);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb,
                                                 size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn,
                                                enum qemu_plugin_op op,
                                                void *ptr, uint64_t imm);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn,
                                            qemu_plugin_vcpu_udata_cb_t cb,
                                            enum qemu_plugin_cb_flags flags,
                                            void *udata);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id,
                                    qemu_plugin_udata_cb_t cb, void *udata);
void qemu_plugin_register_vcpu_tb_exec_cb(struct qemu_plugin_tb *tb,
                                          qemu_plugin_vcpu_udata_cb_t cb,
                                          enum qemu_plugin_cb_flags flags,
                                          void *udata);
uint64_t qemu_plugin_tb_vaddr(const struct qemu_plugin_tb *tb);

#define EXPORT __attribute__((visibility("default")))
EXPORT int qemu_plugin_version = 1;
EXPORT int qemu_plugin_install(qemu_plugin_id_t id,
                               const struct qemu_info_t *info, int argc,
                               char **argv);

/* ---- counting ------------------------------------------------------------- */

static uint64_t executed;   /* one vCPU: plain inline adds are exact */
static uint64_t mark_addr = UINT64_MAX;
static FILE *out;

#define PHASES 8            /* marker buckets; bucket PHASES is "meta" */
#define MAX_META 8
static int have_phases;
static uint64_t phase_addr[PHASES];
static uint64_t meta_lo[MAX_META], meta_hi[MAX_META];
static int meta_count;
static uint64_t bucket[PHASES + 1];
static int current = PHASES - 1;

static void on_mark(unsigned int vcpu, void *udata)
{
    int k;
    (void)vcpu;
    (void)udata;
    fprintf(out, "insn-mark %llu\n", (unsigned long long)executed);
    if (have_phases) {
        fprintf(out, "insn-buckets");
        for (k = 0; k <= PHASES; ++k)
            fprintf(out, " %llu", (unsigned long long)bucket[k]);
        fprintf(out, "\n");
    }
}

/* udata of a block: its instruction count, bit 16 set if it is measurement
 * code, bits 20 and up the marker it starts with, plus one (0: none). */
static void on_block(unsigned int vcpu, void *udata)
{
    uintptr_t u = (uintptr_t)udata;
    unsigned marker = (unsigned)(u >> 20);
    (void)vcpu;
    if (marker)
        current = (int)marker - 1;
    bucket[(u >> 16) & 1u ? PHASES : current] += u & 0xffffu;
}

static void on_translate(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    size_t i, n = qemu_plugin_tb_n_insns(tb);
    (void)id;
    if (have_phases) {
        uint64_t start = qemu_plugin_tb_vaddr(tb) & ~(uint64_t)1;
        uintptr_t u = (uintptr_t)n;
        int k;
        for (k = 0; k < meta_count; ++k)
            if (start >= meta_lo[k] && start < meta_hi[k])
                u |= (uintptr_t)1 << 16;
        for (k = 0; k < PHASES; ++k)
            if (start == phase_addr[k])
                u |= (uintptr_t)(k + 1) << 20;
        qemu_plugin_register_vcpu_tb_exec_cb(tb, on_block, QEMU_PLUGIN_CB_NO_REGS,
                                             (void *)u);
    }
    for (i = 0; i < n; ++i) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        qemu_plugin_register_vcpu_insn_exec_inline(
            insn, QEMU_PLUGIN_INLINE_ADD_U64, &executed, 1);
        if ((qemu_plugin_insn_vaddr(insn) & ~(uint64_t)1) == mark_addr)
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_mark,
                                                   QEMU_PLUGIN_CB_NO_REGS, NULL);
    }
}

static void on_exit_(qemu_plugin_id_t id, void *udata)
{
    (void)id;
    (void)udata;
    fprintf(out, "insn-total %llu\n", (unsigned long long)executed);
    fflush(out);
    if (out != stderr)
        fclose(out);
}

int qemu_plugin_install(qemu_plugin_id_t id, const struct qemu_info_t *info,
                        int argc, char **argv)
{
    int i;
    (void)info;
    out = stderr;
    for (i = 0; i < argc; ++i) {
        if (strncmp(argv[i], "mark=", 5) == 0) {
            mark_addr = strtoull(argv[i] + 5, NULL, 0) & ~(uint64_t)1;
        } else if (strncmp(argv[i], "phase=", 6) == 0) {
            char *p = argv[i] + 6, *end;
            int k;
            for (k = 0; k < PHASES; ++k) {
                phase_addr[k] = strtoull(p, &end, 0) & ~(uint64_t)1;
                if (end == p || (k + 1 < PHASES ? *end != ':' : *end != '\0')) {
                    fprintf(stderr, "insn_count: phase= wants %d addresses "
                                    "separated by ':'\n", PHASES);
                    return 1;
                }
                p = end + 1;
            }
            have_phases = 1;
        } else if (strncmp(argv[i], "meta=", 5) == 0) {
            char *p = argv[i] + 5, *end;
            if (meta_count == MAX_META) {
                fprintf(stderr, "insn_count: at most %d meta= ranges\n", MAX_META);
                return 1;
            }
            meta_lo[meta_count] = strtoull(p, &end, 0) & ~(uint64_t)1;
            if (end == p || *end != ':') {
                fprintf(stderr, "insn_count: meta= wants START:END\n");
                return 1;
            }
            p = end + 1;
            meta_hi[meta_count] = strtoull(p, &end, 0);
            if (end == p || *end != '\0') {
                fprintf(stderr, "insn_count: meta= wants START:END\n");
                return 1;
            }
            meta_count++;
        } else if (strncmp(argv[i], "out=", 4) == 0) {
            out = fopen(argv[i] + 4, "w");
            if (!out) {
                perror(argv[i] + 4);
                return 1;
            }
        } else {
            fprintf(stderr, "insn_count: unknown argument '%s' (mark=ADDR, out=PATH, "
                            "phase=A0:...:A7, meta=START:END)\n",
                    argv[i]);
            return 1;
        }
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_translate);
    qemu_plugin_register_atexit_cb(id, on_exit_, NULL);
    return 0;
}
