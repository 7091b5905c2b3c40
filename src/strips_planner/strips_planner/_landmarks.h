/* Fact landmarks by Zhu & Givan's label propagation (2003), over the relaxed task that _core.c builds: facts
 * 0..nfacts-1, GOAL = nfacts (added by the goal operator), TRUE = nfacts + 1 (in every state).
 *
 * Each fact reached from the initial state gets a label: the facts that every relaxed path to it achieves. An
 * operator's label is the union of its preconditions' labels, and a fact's label is the intersection, over the
 * operators that add it, of their labels plus the fact itself. Labels only shrink once set, so a work list
 * reaches the fixed point. GOAL's label is the landmarks: facts true at some point of every plan (relaxed plans
 * included). Fast Downward's lm_zg computes the same set. */
#ifndef SEMGOAL_PLANNER_LANDMARKS_H
#define SEMGOAL_PLANNER_LANDMARKS_H

#include "_support.h"

/* The landmarks of reaching GOAL from `init` into `out` (nwords words over the facts): 1, or 0 when the relaxed
   task cannot reach GOAL at all (no landmarks then), -1 when out of memory. */
static inline int zhu_givan_landmarks(int nfacts, int nwords, int nops, const Rows *rpre, const Rows *radd,
                                      const Rows *consumers, const word *init, word *out) {
    int nf = nfacts + 2, goal = nfacts, truth = nfacts + 1, top = 0, status = -1;
    size_t nw = (size_t)nwords;
    word *label = calloc((size_t)nf * nw, sizeof(word)), *op_label = malloc(nw * sizeof(word));
    char *reached = calloc((size_t)nf, 1), *counted = calloc((size_t)nf, 1), *queued = calloc((size_t)nf, 1);
    int *missing = malloc(sizeof(int) * (size_t)(nops + 1)), *stack = malloc(sizeof(int) * (size_t)nf);
    if (!label || !op_label || !reached || !counted || !queued || !missing || !stack) goto done;
    for (int o = 0; o <= nops; o++) missing[o] = rpre->start[o + 1] - rpre->start[o];
    for (int f = 0; f < nfacts; f++)
        if (init[f / 64] >> (f % 64) & 1) {
            label[(size_t)f * nw + (size_t)f / 64] |= (word)1 << (f % 64);
            reached[f] = queued[f] = 1;
            stack[top++] = f;
        }
    reached[truth] = queued[truth] = 1; /* its label is empty: every state has it */
    stack[top++] = truth;
    while (top) {
        int f = stack[--top];
        queued[f] = 0;
        for (int k = consumers->start[f]; k < consumers->start[f + 1]; k++) {
            int o = consumers->items[k];
            if (!counted[f]) missing[o]--;
            if (missing[o]) continue;
            memset(op_label, 0, nw * sizeof(word));
            for (int j = rpre->start[o]; j < rpre->start[o + 1]; j++)
                for (size_t i = 0; i < nw; i++) op_label[i] |= label[(size_t)rpre->items[j] * nw + i];
            for (int j = radd->start[o]; j < radd->start[o + 1]; j++) {
                int g = radd->items[j], changed = !reached[g];
                word *into = label + (size_t)g * nw;
                for (size_t i = 0; i < nw; i++) {
                    word own = g < nfacts && (size_t)g / 64 == i ? (word)1 << (g % 64) : 0;
                    word next = reached[g] ? into[i] & (op_label[i] | own) : op_label[i] | own;
                    changed |= next != into[i];
                    into[i] = next;
                }
                reached[g] = 1;
                if (changed && !queued[g]) {
                    queued[g] = 1;
                    stack[top++] = g;
                }
            }
        }
        counted[f] = 1;
    }
    memcpy(out, label + (size_t)goal * nw, nw * sizeof(word));
    status = reached[goal];
done:
    free(label);
    free(op_label);
    free(reached);
    free(counted);
    free(queued);
    free(missing);
    free(stack);
    return status;
}

#endif
