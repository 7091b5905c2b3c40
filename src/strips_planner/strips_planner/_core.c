/* The planner's hot loop in C: forward searches (breadth-first, A*, greedy best-first, eager and lazy) and the
 * heuristics (blind, hmax, hFF, LM-cut, the landmark count) over a grounded STRIPS task.
 *
 * Parsing stays in Python (strips_planner.pddl), grounding in Python and _ground.c; this module gets the
 * ground operators as bit masks (with their conditional effects, each a condition and its adds and deletes) and
 * returns plans as operator indices. It holds the GIL throughout and checks
 * for signals now and then, so Ctrl-C still stops a long search.
 *
 * States are bitsets of `nwords` 64-bit words. The searches keep every state they meet in one arena
 * (parent link, g and h per state) with an open-addressing hash table on top. Successors are generated
 * in the same order as the pure-Python planner that preceded this module (operators filed under their
 * rarest precondition, visited by the state's set bits, lowest first), so breadth-first search returns
 * the very plans it returned.
 *
 * The relaxed heuristics share one structure: the facts plus two artificial ones, "goal" (added by a
 * zero-cost operator that needs the goal facts) and "true" (in every state, and the precondition of
 * operators that have none), and a Dijkstra over facts (Bonet & Geffner 2001; Hoffmann & Nebel 2001;
 * Helmert & Domshlak 2009). A fact some precondition, condition or goal asks to be false has a relaxed fact for its
 * negation too, true where the fact is not and made by what deletes it, as a finite-domain translation (Fast
 * Downward's) has the false value of a binary variable: without it a relaxation ignores negative preconditions
 * (schedule's `(not (busy polisher))`) and cannot see what must be undone first. A conditional effect is a relaxed operator of its own (its operator's precondition and
 * its condition; its adds), as Fast Downward's relaxation heuristics take them; LM-cut is refused on such tasks (it
 * would no longer be admissible). Derived predicates' rules (axioms) make a state's derived facts after every
 * operator, layer by layer to a fixed point; relaxed, each rule is an operator of cost 0, and a negated derived fact
 * is left out (assumed true), as Fast Downward's relaxations take them.
 */
#include "_landmarks.h" /* Zhu & Givan's landmarks */
#include "_support.h"   /* Python.h, word, Rows, int <-> words */

#include <limits.h>
#include <time.h>

#define COST_INF INT_MAX
#define SIGNAL_CHECK_MASK 0xFF /* check for Ctrl-C or an alarm every 256 expansions (a flag's read: free) */
#define DEADLINE_CHECK_MASK 0xF /* read the clock every 16 expansions where a search has a time limit (~25 ns) */

enum { H_BLIND, H_HMAX, H_HFF, H_LMCUT, H_LMCOUNT, H_COUNT };
static const char *const HEURISTIC_NAMES[H_COUNT] = {"blind", "hmax", "hff", "lmcut", "lmcount"};

/* -- small containers ------------------------------------------------------------------------------ */

/* A binary min-heap of (key, item, tie) ordered lexicographically: Python's heapq on tuples. */
typedef struct {
    int key, item;
    int64_t tie;
} Entry;

typedef struct {
    Entry *a;
    size_t n, cap;
} Heap;

static int entry_less(const Entry *x, const Entry *y) {
    if (x->key != y->key) return x->key < y->key;
    if (x->tie != y->tie) return x->tie < y->tie;
    return x->item < y->item;
}

static int heap_push(Heap *heap, int key, int64_t tie, int item) {
    if (heap->n == heap->cap) {
        size_t cap = heap->cap ? heap->cap * 2 : 256;
        Entry *a = realloc(heap->a, cap * sizeof(Entry));
        if (!a) return -1;
        heap->a = a;
        heap->cap = cap;
    }
    size_t i = heap->n++;
    Entry e = {key, item, tie};
    while (i > 0) {
        size_t up = (i - 1) / 2;
        if (!entry_less(&e, &heap->a[up])) break;
        heap->a[i] = heap->a[up];
        i = up;
    }
    heap->a[i] = e;
    return 0;
}

static Entry heap_pop(Heap *heap) {
    Entry top = heap->a[0], last = heap->a[--heap->n];
    size_t i = 0, n = heap->n;
    for (;;) {
        size_t child = 2 * i + 1;
        if (child >= n) break;
        if (child + 1 < n && entry_less(&heap->a[child + 1], &heap->a[child])) child++;
        if (!entry_less(&heap->a[child], &last)) break;
        heap->a[i] = heap->a[child];
        i = child;
    }
    if (n) heap->a[i] = last;
    return top;
}

/* -- the task ---------------------------------------------------------------------------------------- */

typedef struct {
    PyObject_HEAD
    int nfacts, nwords, nops;
    word *pre, *neg, *add, *keep; /* nops x nwords each; keep = ~delete */
    int ncond, *cond_start, *cond_op;   /* conditional effects: operator o's are cond_start[o]..cond_start[o + 1], and
                                           cond_op names each one's operator */
    word *cpre, *cneg, *cadd, *cdel;    /* ncond x nwords each: an effect's condition, its adds and its deletes */
    int nax, *ax_layer, *ax_head;       /* derived predicates' rules, layer by layer: each one's layer and head fact */
    word *ax_pos, *ax_neg, *derived;    /* nax x nwords each: a rule's body; and the derived facts' mask */
    int nrel;                           /* relaxed operators: the operators, one per conditional effect, one per
                                           rule */
    int nneg, *neg_of, *neg_index;      /* negated facts: relaxed fact nfacts + k is "not neg_of[k]"; neg_index:
                                           per fact, its k or -1 */
    int nrf;                            /* relaxed facts: the facts, then the negated ones */
    word *init, *goal, *goal_neg;
    Rows filed;                   /* per fact: operators filed under it (their rarest precondition) */
    int *free_ops, nfree;         /* operators with no positive precondition */
    /* the relaxed task: facts 0..nfacts-1, the negated facts nfacts..nrf-1, GOAL = nrf, TRUE = nrf + 1; operators
       0..nops-1, the conditional effects nops..nrel-1 and the goal operator nrel */
    Rows rpre, radd, consumers, achievers;
    /* heuristic workspace, reused between evaluations */
    int *fact_cost, *achiever, *missing, *supporter, *op_max; /* achiever: each fact's cheapest, for hFF */
    int *base_cost, *cost; /* the operators' costs, 0 for the goal operator; LM-cut's costs, lowered by its cuts */
    int unit, min_cost;    /* whether every operator costs 1; the cheapest operator's cost */
    int *mark, *in_zone, *op_mark, *stack, *cut; /* marks hold the epoch of their last use */
    int epoch;
    Heap heap;
    word *landmarks;    /* Zhu & Givan's, from the initial state; NULL until a search or an evaluation needs them */
    int nlm, *lm_fact;  /* the landmarks, fact by fact */
    word *lm_needs;     /* nlm x nwords: per landmark, the landmarks ordered greedy-necessarily before it (a precondition
                           of every operator that adds it), then nwords words of workspace */
    int goal_reachable; /* in the relaxed task from the initial state; set with the landmarks */
} TaskObject;

#define W(t, arr, o) ((arr) + (size_t)(o) * (size_t)(t)->nwords)

static int applicable(const TaskObject *t, const word *s, int o) {
    const word *pre = W(t, t->pre, o), *neg = W(t, t->neg, o);
    for (int i = 0; i < t->nwords; i++)
        if ((s[i] & pre[i]) != pre[i] || (s[i] & neg[i])) return 0;
    return 1;
}

static int effect_fires(const TaskObject *t, const word *s, int c) {
    const word *pre = W(t, t->cpre, c), *neg = W(t, t->cneg, c);
    for (int i = 0; i < t->nwords; i++)
        if ((s[i] & pre[i]) != pre[i] || (s[i] & neg[i])) return 0;
    return 1;
}

/* Operator o's conditional effects onto `child` (its own effects already made): every condition read in `s`, the
   deletes before the adds (an atom both added and deleted is true after, as in Fast Downward). Kept out of line, so
   that a STRIPS task's children cost what they did. */
static __attribute__((noinline)) void apply_effects(const TaskObject *t, const word *s, int o, word *child) {
    int first = t->cond_start[o], last = t->cond_start[o + 1];
    if (first == last) return;
    char fires[last - first];
    for (int c = first; c < last; c++) {
        fires[c - first] = (char)effect_fires(t, s, c);
        if (!fires[c - first]) continue;
        const word *del = W(t, t->cdel, c);
        for (int i = 0; i < t->nwords; i++) child[i] &= ~del[i];
    }
    const word *add = W(t, t->add, o);
    for (int c = first; c < last; c++) {
        const word *cadd = W(t, t->cadd, c);
        if (fires[c - first])
            for (int i = 0; i < t->nwords; i++) child[i] |= cadd[i];
    }
    for (int i = 0; i < t->nwords; i++) child[i] |= add[i];
}

/* State `s`'s derived facts made again: cleared, then each layer's rules applied to their fixed point. */
static __attribute__((noinline)) void derive(const TaskObject *t, word *s) {
    for (int i = 0; i < t->nwords; i++) s[i] &= ~t->derived[i];
    for (int first = 0, last; first < t->nax; first = last) {
        for (last = first; last < t->nax && t->ax_layer[last] == t->ax_layer[first]; last++) {}
        for (int changed = 1; changed;) {
            changed = 0;
            for (int r = first; r < last; r++) {
                int h = t->ax_head[r];
                if (s[h / 64] >> (h % 64) & 1) continue;
                const word *pos = W(t, t->ax_pos, r), *neg = W(t, t->ax_neg, r);
                int fires = 1;
                for (int i = 0; i < t->nwords && fires; i++) fires = (s[i] & pos[i]) == pos[i] && !(s[i] & neg[i]);
                if (fires) s[h / 64] |= (word)1 << (h % 64), changed = 1;
            }
        }
    }
}

/* The child of `s` by operator o. */
static inline void apply_op(const TaskObject *t, const word *s, int o, word *child) {
    const word *keep = W(t, t->keep, o), *add = W(t, t->add, o);
    for (int i = 0; i < t->nwords; i++) child[i] = (s[i] & keep[i]) | add[i];
    if (t->ncond) apply_effects(t, s, o, child);
    if (t->nax) derive(t, child);
}

static int goal_reached(const TaskObject *t, const word *s) {
    for (int i = 0; i < t->nwords; i++)
        if ((s[i] & t->goal[i]) != t->goal[i] || (s[i] & t->goal_neg[i])) return 0;
    return 1;
}

/* Applicable operators of `s` into `out` (room for nops), in generation order; returns the count. */
static int applicable_ops(const TaskObject *t, const word *s, int *out) {
    int n = 0;
    for (int k = 0; k < t->nfree; k++)
        if (applicable(t, s, t->free_ops[k])) out[n++] = t->free_ops[k];
    for (int i = 0; i < t->nwords; i++) {
        word rest = s[i];
        while (rest) {
            int f = i * 64 + __builtin_ctzll(rest);
            rest &= rest - 1;
            for (int k = t->filed.start[f]; k < t->filed.start[f + 1]; k++) {
                int o = t->filed.items[k];
                if (applicable(t, s, o)) out[n++] = o;
            }
        }
    }
    return n;
}

/* -- heuristics -------------------------------------------------------------------------------------- */

static int in_state(const word *s, int f) { return (int)(s[f / 64] >> (f % 64) & 1); }

/* Whether relaxed fact f (not GOAL or TRUE) holds in state `s`. */
static int relaxed_true(const TaskObject *t, const word *s, int f) {
    return f < t->nfacts ? in_state(s, f) : !in_state(s, t->neg_of[f - t->nfacts]);
}

/* The relaxed facts of state `s` into `out` (room for nrf): its facts, then the negated facts of those it lacks;
   returns how many. */
static int state_facts(const TaskObject *t, const word *s, int *out) {
    int n = 0;
    for (int i = 0; i < t->nwords; i++)
        for (word rest = s[i]; rest; rest &= rest - 1) out[n++] = i * 64 + __builtin_ctzll(rest);
    for (int k = 0; k < t->nneg; k++)
        if (!in_state(s, t->neg_of[k])) out[n++] = t->nfacts + k;
    return n;
}

static int next_epoch(TaskObject *t) {
    if (t->epoch == INT_MAX) {
        memset(t->mark, 0, sizeof(int) * (size_t)(t->nrf + 2));
        memset(t->in_zone, 0, sizeof(int) * (size_t)(t->nrf + 2));
        memset(t->op_mark, 0, sizeof(int) * (size_t)(t->nrel + 1));
        t->epoch = 0;
    }
    return ++t->epoch;
}

/* The Dijkstra over facts: lower the cost of every fact that operator o adds to `value`, where that is
   cheaper (o becomes its cheapest achiever). */
static int offer(TaskObject *t, int o, int value) {
    for (int k = t->radd.start[o]; k < t->radd.start[o + 1]; k++) {
        int g = t->radd.items[k];
        if (value < t->fact_cost[g]) {
            t->fact_cost[g] = value;
            t->achiever[g] = o;
            if (heap_push(&t->heap, value, g, g)) return -1;
        }
    }
    return 0;
}

/* The start of a Dijkstra over facts from state `s`: the facts of `s` and "true" cost 0 and wait in the heap, the
   others are unreached, and every operator misses all its preconditions (op_max 0, no supporter yet). */
static int dijkstra_start(TaskObject *t, const word *s) {
    int nf = t->nrf + 2, nr = t->nrel + 1, truth = t->nrf + 1, *facts = t->stack;
    for (int f = 0; f < nf; f++) t->fact_cost[f] = COST_INF;
    for (int o = 0; o < nr; o++) {
        t->missing[o] = t->rpre.start[o + 1] - t->rpre.start[o];
        t->supporter[o] = -1;
        t->op_max[o] = 0;
    }
    t->heap.n = 0;
    for (int k = 0, n = state_facts(t, s, facts); k < n; k++) {
        t->fact_cost[facts[k]] = 0;
        if (heap_push(&t->heap, 0, facts[k], facts[k])) return -1;
    }
    t->fact_cost[truth] = 0;
    return heap_push(&t->heap, 0, truth, truth);
}

/* hmax costs of all facts from state `s` under LM-cut's operator costs t->cost: Dijkstra over facts.
   Facts pop in order of cost (ties: lower fact first), so an operator's last precondition to pop is a
   costliest one: its supporter. */
static int relaxed_costs(TaskObject *t, const word *s) {
    if (dijkstra_start(t, s)) return -1;
    while (t->heap.n) {
        Entry e = heap_pop(&t->heap);
        if (e.key > t->fact_cost[e.item]) continue;
        for (int k = t->consumers.start[e.item]; k < t->consumers.start[e.item + 1]; k++) {
            int o = t->consumers.items[k];
            if (--t->missing[o] == 0) {
                t->supporter[o] = e.item;
                t->op_max[o] = e.key;
                if (offer(t, o, e.key + t->cost[o])) return -1;
            }
        }
    }
    return 0;
}

/* hmax costs from state `s` with every operator costing 1: a breadth-first sweep over facts, which meets
   them in order of cost, so each fact's first achiever is a cheapest one (t->achiever). Only the goal
   operator costs 0, and nothing needs its fact. It stops once the goal fact is set (its cost and every
   achiever a relaxed plan can need are final by then). */
static void unit_costs(TaskObject *t, const word *s) {
    int nf = t->nrf + 2, nr = t->nrel + 1, goal = t->nrf, truth = t->nrf + 1, head = 0, tail = 0;
    int *queue = t->stack;
    for (int f = 0; f < nf; f++) t->fact_cost[f] = COST_INF;
    for (int o = 0; o < nr; o++) t->missing[o] = t->rpre.start[o + 1] - t->rpre.start[o];
    tail = state_facts(t, s, queue);
    for (int k = 0; k < tail; k++) t->fact_cost[queue[k]] = 0;
    t->fact_cost[truth] = 0;
    queue[tail++] = truth;
    while (head < tail) {
        int f = queue[head++], value = t->fact_cost[f];
        for (int k = t->consumers.start[f]; k < t->consumers.start[f + 1]; k++) {
            int o = t->consumers.items[k];
            if (--t->missing[o]) continue;
            for (int j = t->radd.start[o]; j < t->radd.start[o + 1]; j++) {
                int g = t->radd.items[j];
                if (t->fact_cost[g] != COST_INF) continue;
                t->fact_cost[g] = value + t->base_cost[o];
                t->achiever[g] = o;
                if (g == goal) return;
                queue[tail++] = g;
            }
        }
    }
}

/* hmax costs and cheapest achievers of all facts from state `s` under the operators' own costs: the
   breadth-first sweep where every operator costs 1, else the Dijkstra. */
static int hmax_costs(TaskObject *t, const word *s) {
    if (t->unit) {
        unit_costs(t, s);
        return 0;
    }
    memcpy(t->cost, t->base_cost, sizeof(int) * (size_t)(t->nrel + 1));
    return relaxed_costs(t, s);
}

static int h_hmax(TaskObject *t, const word *s) {
    if (hmax_costs(t, s)) return -1;
    return t->fact_cost[t->nrf];
}

static int add_costs(int x, int y) { return x > COST_INF - y ? COST_INF : x + y; }

/* hadd costs and cheapest achievers of the facts from state `s`: an operator costs its own cost plus the sum of
   its preconditions' (Bonet & Geffner 2001). A Dijkstra over facts offers an operator once its last
   precondition pops. It stops when the goal fact pops: every fact a relaxed plan can need is final then (any
   later offer costs at least the goal's). */
static int additive_costs(TaskObject *t, const word *s) {
    int goal = t->nrf, *sum = t->op_max; /* per operator, its popped preconditions' costs so far */
    if (dijkstra_start(t, s)) return -1;
    while (t->heap.n) {
        Entry e = heap_pop(&t->heap);
        if (e.key > t->fact_cost[e.item]) continue;
        if (e.item == goal) break;
        for (int k = t->consumers.start[e.item]; k < t->consumers.start[e.item + 1]; k++) {
            int o = t->consumers.items[k];
            sum[o] = add_costs(sum[o], e.key);
            if (--t->missing[o] == 0 && offer(t, o, add_costs(sum[o], t->base_cost[o]))) return -1;
        }
    }
    return 0;
}

/* The operator a relaxed operator stands for: itself, or a conditional effect's operator. */
static int real_op(const TaskObject *t, int o) {
    return o < t->nops || o >= t->nops + t->ncond ? o : t->cond_op[o - t->nops];
}

/* hFF: the cost of a relaxed plan made of each needed fact's cheapest achiever under hadd (as Fast Downward's
   FF heuristic takes them; Keyder & Geffner 2008), traced back from the goal fact (its size where every
   operator costs 1). An operator counts once however many of its effects the plan uses, and is marked (op_mark)
   as the relaxed plan's, for the helpful operators; its own precondition is in each of its effects'. */
static int h_hff(TaskObject *t, const word *s) {
    if (additive_costs(t, s)) return -1;
    int goal = t->nrf, truth = t->nrf + 1;
    if (t->fact_cost[goal] == COST_INF) return COST_INF;
    int epoch = next_epoch(t), size = 0, top = 0;
    t->stack[top++] = goal;
    t->mark[goal] = epoch;
    while (top) {
        int f = t->stack[--top];
        if (f == truth || (f < goal && relaxed_true(t, s, f))) continue;
        int o = t->achiever[f], real = real_op(t, o);
        if (t->op_mark[o] == epoch) continue;
        if (real == o || t->op_mark[real] != epoch) size += t->base_cost[o];
        t->op_mark[o] = t->op_mark[real] = epoch;
        for (int k = t->rpre.start[o]; k < t->rpre.start[o + 1]; k++) {
            int p = t->rpre.items[k];
            if (t->mark[p] != epoch) {
                t->mark[p] = epoch;
                t->stack[top++] = p;
            }
        }
    }
    return size;
}

/* After the operators in t->cut[0..ncut) got cheaper, update the hmax costs: costs only ever fall, so
   only what those operators reach can change (the incremental hmax of LM-cut). */
static int lower_costs(TaskObject *t, int ncut) {
    t->heap.n = 0;
    for (int k = 0; k < ncut; k++)
        if (offer(t, t->cut[k], t->op_max[t->cut[k]] + t->cost[t->cut[k]])) return -1;
    while (t->heap.n) {
        Entry e = heap_pop(&t->heap);
        if (e.key > t->fact_cost[e.item]) continue;
        for (int k = t->consumers.start[e.item]; k < t->consumers.start[e.item + 1]; k++) {
            int o = t->consumers.items[k];
            if (t->supporter[o] != e.item) continue;
            /* the costliest precondition fell: find the new one */
            int best = e.item; /* ties keep it: a change of supporter on a tie weakens the cuts */
            for (int j = t->rpre.start[o]; j < t->rpre.start[o + 1]; j++) {
                int p = t->rpre.items[j];
                if (t->fact_cost[p] > t->fact_cost[best]) best = p;
            }
            t->supporter[o] = best;
            if (t->fact_cost[best] < t->op_max[o]) {
                t->op_max[o] = t->fact_cost[best];
                if (offer(t, o, t->op_max[o] + t->cost[o])) return -1;
            }
        }
    }
    return 0;
}

/* A zero-cost operator met while the goal zone grows: among its costliest preconditions, take as its supporter
   one that no zero-cost operator achieves (the zone's border) or one already in the zone, where there is such
   a tie. Any costliest precondition keeps LM-cut admissible; these give larger cuts (Fast Downward breaks
   the same ties this way). */
static void break_ties(TaskObject *t, int o, int zone) {
    int cost = t->fact_cost[t->supporter[o]];
    for (int j = t->rpre.start[o]; j < t->rpre.start[o + 1]; j++) {
        int p = t->rpre.items[j];
        if (t->fact_cost[p] != cost) continue;
        int border = 1;
        for (int k = t->achievers.start[p]; k < t->achievers.start[p + 1] && border; k++)
            border = t->cost[t->achievers.items[k]] != 0;
        if (border || t->in_zone[p] == zone) {
            t->supporter[o] = p;
            return;
        }
    }
}

/* LM-cut: the sum of the costs of disjunctive action landmarks found by repeated hmax cuts. */
static int h_lmcut(TaskObject *t, const word *s) {
    int nr = t->nrel + 1, goal = t->nrf, truth = t->nrf + 1;
    memcpy(t->cost, t->base_cost, sizeof(int) * (size_t)nr);
    if (relaxed_costs(t, s)) return -1;
    if (t->fact_cost[goal] == COST_INF) return COST_INF;
    int total = 0;
    while (t->fact_cost[goal] > 0) {
        /* the goal zone: facts that reach the goal through zero-cost operators, via their supporters */
        int zone = next_epoch(t), top = 0;
        t->in_zone[goal] = zone;
        t->stack[top++] = goal;
        while (top) {
            int f = t->stack[--top];
            for (int k = t->achievers.start[f]; k < t->achievers.start[f + 1]; k++) {
                int o = t->achievers.items[k];
                if (t->cost[o] != 0 || t->supporter[o] < 0) continue;
                break_ties(t, o, zone);
                int p = t->supporter[o];
                if (t->in_zone[p] != zone) {
                    t->in_zone[p] = zone;
                    t->stack[top++] = p;
                }
            }
        }
        /* forward from the state through operators whose supporter is reached, stopping at the zone */
        int reached = zone, ncut = 0;
        top = state_facts(t, s, t->stack);
        for (int k = 0; k < top; k++) t->mark[t->stack[k]] = reached;
        t->mark[truth] = reached;
        t->stack[top++] = truth;
        while (top) {
            int f = t->stack[--top];
            for (int k = t->consumers.start[f]; k < t->consumers.start[f + 1]; k++) {
                int o = t->consumers.items[k];
                if (t->supporter[o] != f) continue;
                int into_zone = 0;
                for (int j = t->radd.start[o]; j < t->radd.start[o + 1]; j++)
                    into_zone |= t->in_zone[t->radd.items[j]] == zone;
                if (into_zone) {
                    if (t->op_mark[o] != reached) {
                        t->op_mark[o] = reached;
                        t->cut[ncut++] = o;
                    }
                    continue;
                }
                for (int j = t->radd.start[o]; j < t->radd.start[o + 1]; j++) {
                    int g = t->radd.items[j];
                    if (t->mark[g] != reached) {
                        t->mark[g] = reached;
                        t->stack[top++] = g;
                    }
                }
            }
        }
        int step = COST_INF;
        for (int k = 0; k < ncut; k++)
            if (t->cost[t->cut[k]] < step) step = t->cost[t->cut[k]];
        if (ncut == 0 || step == 0) break; /* a degenerate cut: the sum so far is still a lower bound */
        total += step;
        for (int k = 0; k < ncut; k++) t->cost[t->cut[k]] -= step;
        if (lower_costs(t, ncut)) return -1;
    }
    return total;
}

/* The greedy-necessary orderings among `landmarks` (Hoffmann, Porteous & Sebastia 2004): landmark A comes right
   before landmark B where A is a precondition of every operator that adds B. Only these say a landmark is needed
   again once it has been made false (LAMA's "required again", Richter & Westphal 2010). 0, or -1 when out of
   memory. */
static int order_landmarks(TaskObject *t, const word *landmarks) {
    size_t nw = (size_t)t->nwords;
    int n = 0;
    for (size_t i = 0; i < nw; i++) n += __builtin_popcountll(landmarks[i]);
    t->lm_fact = malloc(sizeof(int) * (size_t)(n ? n : 1));
    t->lm_needs = calloc(((size_t)n + 1) * nw, sizeof(word));
    if (!t->lm_fact || !t->lm_needs) return -1;
    t->nlm = 0;
    for (int f = 0; f < t->nfacts; f++) {
        if (!(landmarks[f / 64] >> (f % 64) & 1)) continue;
        word *needs = t->lm_needs + (size_t)t->nlm * nw;
        t->lm_fact[t->nlm++] = f;
        for (int k = t->achievers.start[f]; k < t->achievers.start[f + 1]; k++) {
            word *shared = t->lm_needs + (size_t)n * nw; /* the workspace: this achiever's preconditions */
            memset(shared, 0, nw * sizeof(word));
            int o = t->achievers.items[k];
            for (int j = t->rpre.start[o]; j < t->rpre.start[o + 1]; j++)
                if (t->rpre.items[j] < t->nfacts) shared[t->rpre.items[j] / 64] |= (word)1 << (t->rpre.items[j] % 64);
            for (size_t i = 0; i < nw; i++) needs[i] = k == t->achievers.start[f] ? shared[i] & landmarks[i] : needs[i] & shared[i];
        }
    }
    return 0;
}

/* The task's landmarks, found on first use over the relaxed facts; the count keeps the facts' own (a negated fact
   is no fact of a state); -1 when out of memory. */
static int find_landmarks(TaskObject *t) {
    if (t->landmarks) return 0;
    int rwords = (t->nrf + 63) / 64 + 1, reachable = -1;
    word *init = calloc((size_t)rwords, sizeof(word)), *found = malloc(sizeof(word) * (size_t)rwords);
    if (init && found) {
        for (int k = 0, n = state_facts(t, t->init, t->stack); k < n; k++)
            init[t->stack[k] / 64] |= (word)1 << (t->stack[k] % 64);
        reachable = zhu_givan_landmarks(t->nrf, rwords, t->nrel, &t->rpre, &t->radd, &t->consumers, init, found);
    }
    free(init);
    if (reachable < 0) {
        free(found);
        return -1;
    }
    for (int f = t->nfacts; f < t->nwords * 64; f++) found[f / 64] &= ~((word)1 << (f % 64)); /* padding and negations */
    if (reachable && order_landmarks(t, found)) {
        free(found);
        return -1;
    }
    t->landmarks = found;
    t->goal_reachable = reachable;
    return 0;
}

/* The landmark count (LAMA's, Richter & Westphal 2010): the landmarks not yet accepted on the path to state `s`,
   plus those accepted but false in `s` that are needed again: the goals, and those ordered greedy-necessarily before
   a landmark not yet accepted (order_landmarks). `accepted` holds the landmarks true in some state of the path (the searches
   keep it per state); NULL takes `s` as the path's only state. Inadmissible: one operator can add several
   landmarks. */
static int h_lmcount(TaskObject *t, const word *s, const word *accepted) {
    if (find_landmarks(t)) return -1;
    if (!t->goal_reachable) return COST_INF;
    int count = 0;
    size_t nw = (size_t)t->nwords;
    word *again = t->lm_needs + (size_t)t->nlm * nw;
    memset(again, 0, nw * sizeof(word));
    for (int k = 0; k < t->nlm; k++) {
        int f = t->lm_fact[k];
        word done = accepted ? accepted[f / 64] : t->landmarks[f / 64] & s[f / 64];
        if (done >> (f % 64) & 1) continue;
        const word *needs = t->lm_needs + (size_t)k * nw;
        for (size_t i = 0; i < nw; i++) again[i] |= needs[i];
    }
    for (size_t i = 0; i < nw; i++) {
        word done = accepted ? accepted[i] : t->landmarks[i] & s[i];
        count += __builtin_popcountll(t->landmarks[i] & ~done) + __builtin_popcountll((t->goal[i] | again[i]) & done & ~s[i]);
    }
    return count;
}

/* h(s) >= 0, COST_INF for a dead end, -1 (MemoryError set) when out of memory. `accepted`: the landmark count's
   accepted landmarks on the path to `s`, or NULL. */
static int evaluate(TaskObject *t, int heuristic, const word *s, const word *accepted) {
    int h;
    switch (heuristic) {
    case H_HMAX: h = h_hmax(t, s); break;
    case H_HFF: h = h_hff(t, s); break;
    case H_LMCUT: h = h_lmcut(t, s); break;
    case H_LMCOUNT: h = h_lmcount(t, s, accepted); break;
    default: return goal_reached(t, s) ? 0 : t->min_cost;
    }
    if (h < 0) PyErr_NoMemory();
    return h;
}

/* -- the state store --------------------------------------------------------------------------------- */

typedef struct {
    int nwords;
    word *states;
    int *parent, *op, *g, *h;
    const word *landmarks; /* when the landmark count guides the search: the task's landmarks */
    word *accepted;        /* then, per state: the landmarks true somewhere on the path it was first reached by */
    size_t n, cap;
    int32_t *slots; /* open addressing: state index + 1, 0 for empty */
    size_t nslots;
} Store;

static uint64_t hash_state(const word *s, int nwords) {
    uint64_t h = 0x9E3779B97F4A7C15ull;
    for (int i = 0; i < nwords; i++) {
        h ^= s[i];
        h *= 0xFF51AFD7ED558CCDull;
        h ^= h >> 32;
    }
    return h;
}

static void store_free(Store *st) {
    free(st->states);
    free(st->parent);
    free(st->op);
    free(st->g);
    free(st->h);
    free(st->accepted);
    free(st->slots);
}

static int store_rehash(Store *st, size_t nslots) {
    int32_t *slots = calloc(nslots, sizeof(int32_t));
    if (!slots) return -1;
    for (size_t k = 0; k < st->n; k++) {
        size_t i = hash_state(st->states + k * (size_t)st->nwords, st->nwords) & (nslots - 1);
        while (slots[i]) i = (i + 1) & (nslots - 1);
        slots[i] = (int32_t)(k + 1);
    }
    free(st->slots);
    st->slots = slots;
    st->nslots = nslots;
    return 0;
}

static int grow(void **p, size_t size) {
    void *q = realloc(*p, size);
    if (!q) return -1;
    *p = q;
    return 0;
}

/* The index of state `s` (whose hash_state is `hash`), added (with *added = 1) if new; -1 when out of memory. */
static long store_find_or_add(Store *st, const word *s, uint64_t hash, int *added) {
    size_t nw = (size_t)st->nwords, i = hash & (st->nslots - 1);
    for (; st->slots[i]; i = (i + 1) & (st->nslots - 1)) {
        size_t k = (size_t)st->slots[i] - 1;
        if (!memcmp(st->states + k * nw, s, nw * sizeof(word))) {
            *added = 0;
            return (long)k;
        }
    }
    if (st->n >= INT32_MAX - 1) return -1;
    if (st->n == st->cap) {
        size_t cap = st->cap ? st->cap * 2 : 1024;
        if (grow((void **)&st->states, cap * nw * sizeof(word)) || grow((void **)&st->parent, cap * sizeof(int)) ||
            grow((void **)&st->op, cap * sizeof(int)) || grow((void **)&st->g, cap * sizeof(int)) ||
            grow((void **)&st->h, cap * sizeof(int)) ||
            (st->landmarks && grow((void **)&st->accepted, cap * nw * sizeof(word))))
            return -1;
        st->cap = cap;
    }
    size_t k = st->n++;
    memcpy(st->states + k * nw, s, nw * sizeof(word));
    st->slots[i] = (int32_t)(k + 1);
    if (2 * st->n > st->nslots && store_rehash(st, st->nslots * 2)) return -1;
    *added = 1;
    return (long)k;
}

static int store_init(Store *st, int nwords) {
    memset(st, 0, sizeof(*st));
    st->nwords = nwords;
    return store_rehash(st, 2048);
}

/* -- searches ---------------------------------------------------------------------------------------- */

typedef struct {
    long goal_state; /* -1: none reachable */
    long expanded, generated;
    double deadline; /* CLOCK_MONOTONIC seconds at which the search stops (0: none) */
    int timed_out;   /* 1 where the search stopped at `deadline` */
} Outcome;

static double monotonic_seconds(void) {
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec + 1e-9 * (double)now.tv_nsec;
}

/* Counts an expansion; 1 where the deadline has passed (recorded in `out`, the clock read every
   DEADLINE_CHECK_MASK + 1 expansions), -1 where a signal stops the search (Ctrl-C, an alarm); else 0. */
static int counting(Outcome *out) {
    ++out->expanded;
    if (out->deadline > 0 && !(out->expanded & DEADLINE_CHECK_MASK) && monotonic_seconds() >= out->deadline) {
        out->timed_out = 1;
        return 1;
    }
    return !(out->expanded & SIGNAL_CHECK_MASK) && PyErr_CheckSignals() ? -1 : 0;
}

typedef enum { S_BFS, S_ASTAR, S_GBFS, S_LAZY } SearchKind;

/* Adds state `s` (whose hash_state is `hash`) reached from `parent` by `op` at depth g; returns its index, or -1
   with an error set. *added says whether it is new. */
static long meet_hashed(Store *st, const word *s, uint64_t hash, long parent, int op, int g, int *added) {
    long k = store_find_or_add(st, s, hash, added);
    if (k < 0) {
        PyErr_NoMemory();
        return -1;
    }
    if (*added) {
        st->parent[k] = (int)parent;
        st->op[k] = op;
        st->g[k] = g;
        st->h[k] = -1;
        for (int i = 0; st->landmarks && i < st->nwords; i++) {
            word before = parent >= 0 ? st->accepted[(size_t)parent * (size_t)st->nwords + (size_t)i] : 0;
            st->accepted[(size_t)k * (size_t)st->nwords + (size_t)i] = before | (st->landmarks[i] & s[i]);
        }
    }
    return k;
}

static long meet(Store *st, const word *s, long parent, int op, int g, int *added) {
    return meet_hashed(st, s, hash_state(s, st->nwords), parent, op, g, added);
}

/* Breadth-first: the store's insertion order is the queue; goal test on generation. A state's children are
   built and hashed first, and their slots, then the states in those slots, prefetched: the lookups that follow
   (most children are states seen before) then overlap their waits on memory instead of taking them one by one
   (blocksworld with 10 blocks: 4 million states, about two cache misses per lookup). */
static int run_bfs(TaskObject *t, Store *st, int *ops, Outcome *out) {
    size_t nw = (size_t)t->nwords, room = (size_t)(t->nops ? t->nops : 1);
    word *kids = malloc(sizeof(word) * nw * room);
    uint64_t *hashes = malloc(sizeof(uint64_t) * room);
    int added, status = 0;
    if (!kids || !hashes) {
        PyErr_NoMemory();
        status = -1;
    }
    for (size_t next = 0; !status && next < st->n; next++) {
        int stop = counting(out);
        if (stop) {
            status = stop > 0 ? 0 : -1;
            break;
        }
        int nops = applicable_ops(t, st->states + next * nw, ops);
        for (int k = 0; k < nops; k++) {
            apply_op(t, st->states + next * nw, ops[k], kids + (size_t)k * nw);
            hashes[k] = hash_state(kids + (size_t)k * nw, t->nwords);
            __builtin_prefetch(st->slots + (hashes[k] & (st->nslots - 1)));
        }
        for (int k = 0; k < nops; k++) {
            int32_t slot = st->slots[hashes[k] & (st->nslots - 1)];
            if (slot) __builtin_prefetch(st->states + (size_t)(slot - 1) * nw);
        }
        for (int k = 0; k < nops; k++) {
            const word *child = kids + (size_t)k * nw;
            long c = meet_hashed(st, child, hashes[k], (long)next, ops[k], st->g[next] + 1, &added);
            if (c < 0) {
                status = -1;
                break;
            }
            if (!added) continue;
            out->generated++;
            if (goal_reached(t, child)) {
                out->goal_state = c;
                goto done;
            }
        }
    }
done:
    free(kids);
    free(hashes);
    return status;
}

/* The searches' goal test on expansion: 1 when state `s` satisfies the goal (recorded in `out`) or the search's
   time is up, -1 when a signal stops the search (Ctrl-C, an alarm), else 0 (and the expansion is counted). */
static int expanding(const TaskObject *t, const word *state, long s, Outcome *out) {
    if (goal_reached(t, state)) {
        out->goal_state = s;
        return 1;
    }
    return counting(out);
}

/* A*: f = g + h, ties to the larger g, then first in; a state reached with a smaller g is reopened. Goal test
   on expansion. */
static int run_astar(TaskObject *t, Store *st, int heuristic, word *child, int *ops, Outcome *out) {
    Heap open = {0};
    int added, status = -1;
    int64_t counter = 0;
    int h0 = evaluate(t, heuristic, st->states, NULL);
    if (h0 < 0) goto done;
    st->h[0] = h0;
    if (h0 == COST_INF) {
        status = 0;
        goto done;
    }
    /* entries: key f, tie -g * 2^40 + counter */
    if (heap_push(&open, h0, 0, 0)) goto oom;
    while (open.n) {
        Entry e = heap_pop(&open);
        long s = e.item;
        if (e.key - st->h[s] > st->g[s]) continue; /* reached more cheaply since */
        const word *state = st->states + (size_t)s * (size_t)st->nwords;
        int stop = expanding(t, state, s, out);
        if (stop) {
            status = stop > 0 ? 0 : -1;
            goto done;
        }
        int g = st->g[s], nops = applicable_ops(t, state, ops);
        for (int k = 0; k < nops; k++) {
            apply_op(t, st->states + (size_t)s * (size_t)st->nwords, ops[k], child);
            int gc = g + t->base_cost[ops[k]];
            long c = meet(st, child, s, ops[k], gc, &added);
            if (c < 0) goto done;
            if (!added) {
                if (gc >= st->g[c]) continue;
                st->parent[c] = (int)s;
                st->op[c] = ops[k];
                st->g[c] = gc;
            }
            if (st->h[c] < 0) {
                int h = evaluate(t, heuristic, child, NULL);
                if (h < 0) goto done;
                st->h[c] = h;
            }
            out->generated++;
            if (st->h[c] == COST_INF) continue;
            counter++;
            int64_t tie = -(int64_t)gc * ((int64_t)1 << 40) + counter;
            if (heap_push(&open, gc + st->h[c], tie, (int)c)) goto oom;
        }
    }
    status = 0;
    goto done;
oom:
    PyErr_NoMemory();
done:
    free(open.a);
    return status;
}

/* -- greedy searches: one open list per heuristic, taking turns ----------------------------------------- */

#define MAX_HEURISTICS 4
/* Turns ahead for the helpful lists at each better value. Fast Downward gives 1000. With hFF and the landmark count
   both reporting progress, 100 solved grid prob05 in 1.3-1.6 s, where 1000 did not within 10 s, and on the IPC
   problems 7-12 of 17 domains 98 of 102, where 1000 solved 97, as did hFF alone at 1000. */
#define BOOST 100

/* What guides a greedy search: its heuristics (taking turns, LAMA's alternation; Richter & Westphal 2010), and
   whether hFF among them names helpful operators (the operators of its relaxed plan from the state expanded;
   Hoffmann & Nebel 2001). The states reached by one wait in a second list per heuristic, and those lists get
   BOOST turns ahead whenever a heuristic finds a better value (boosted preferred operators, as in Fast Downward;
   Richter & Helmert 2009). */
typedef struct {
    int heuristics[MAX_HEURISTICS], n, helpful;
    Heap lists[2 * MAX_HEURISTICS]; /* per heuristic, every state; then per heuristic, those by a helpful operator */
    int turns[2 * MAX_HEURISTICS], best[MAX_HEURISTICS];
} Guide;

static int guide_lists(const Guide *gd) { return gd->helpful ? 2 * gd->n : gd->n; }

static void guide_free(Guide *gd) {
    for (int q = 0; q < 2 * MAX_HEURISTICS; q++) free(gd->lists[q].a);
}

/* The list whose turn it is: the non-empty one with the fewest turns (ties: the first, as in Fast Downward's
   alternation); -1 when all are empty. */
static int guide_turn(Guide *gd) {
    int q = -1;
    for (int i = 0; i < guide_lists(gd); i++)
        if (gd->lists[i].n && (q < 0 || gd->turns[i] < gd->turns[q])) q = i;
    if (q >= 0) gd->turns[q]++;
    return q;
}

/* Every heuristic's value of state `s` into h (hFF last, so that its relaxed plan names the helpful operators):
   1 when one of them calls `s` a dead end, else 0 (the lists with helpful operators boosted when one found a
   better value than before); -1 when out of memory. */
static int guide_evaluate(Guide *gd, TaskObject *t, const word *s, const word *accepted, int *h) {
    int dead = 0, progress = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < gd->n; i++) {
            if ((gd->heuristics[i] == H_HFF) != pass) continue;
            if ((h[i] = evaluate(t, gd->heuristics[i], s, accepted)) < 0) return -1;
            dead |= h[i] == COST_INF;
        }
    for (int i = 0; i < gd->n && !dead; i++)
        if (h[i] < gd->best[i]) {
            progress |= gd->best[i] != COST_INF;
            gd->best[i] = h[i];
        }
    for (int q = gd->n; progress && q < guide_lists(gd); q++) gd->turns[q] -= BOOST;
    return dead;
}

/* Item `item` into each heuristic's list under its value in h (the landmark count's lists first taking those
   `lm_ahead` landmarks nearer, among equal values), and into the helpful lists too where `helpful`. */
static int guide_push(Guide *gd, const int *h, int64_t tie, int lm_ahead, int item, int helpful) {
    for (int i = 0; i < gd->n; i++) {
        int64_t own = gd->heuristics[i] == H_LMCOUNT ? tie - ((int64_t)lm_ahead << 40) : tie;
        if (heap_push(&gd->lists[i], h[i], own, item) || (helpful && heap_push(&gd->lists[gd->n + i], h[i], own, item)))
            return -1;
    }
    return 0;
}

#define ACCEPTED(st, s) ((st)->accepted ? (st)->accepted + (size_t)(s) * (size_t)(st)->nwords : NULL)

/* Greedy best-first: h, then first in; a state is evaluated when it is first reached and expanded once. Goal
   test on expansion. */
static int run_greedy(TaskObject *t, Store *st, Guide *gd, word *child, int *ops, Outcome *out) {
    int added, status = -1, h[MAX_HEURISTICS];
    int64_t counter = 0;
    char *helpful = calloc((size_t)(t->nops ? t->nops : 1), 1), *closed = NULL;
    size_t nclosed = 0;
    if (!helpful) goto oom;
    int dead = guide_evaluate(gd, t, st->states, ACCEPTED(st, 0), h);
    if (dead < 0) goto done;
    st->h[0] = h[0];
    if (dead) {
        status = 0;
        goto done;
    }
    if (guide_push(gd, h, 0, 0, 0, 0)) goto oom;
    for (int q; (q = guide_turn(gd)) >= 0;) {
        long s = heap_pop(&gd->lists[q]).item;
        if ((size_t)s >= nclosed) {
            if (grow((void **)&closed, st->cap)) goto oom;
            memset(closed + nclosed, 0, st->cap - nclosed);
            nclosed = st->cap;
        }
        if (closed[s]) continue; /* it waited in several lists */
        closed[s] = 1;
        const word *state = st->states + (size_t)s * (size_t)st->nwords;
        int stop = expanding(t, state, s, out);
        if (stop) {
            status = stop > 0 ? 0 : -1;
            goto done;
        }
        int g = st->g[s], nops = applicable_ops(t, state, ops);
        if (gd->helpful) { /* hFF again, for the operators of its relaxed plan from this state */
            int hff = h_hff(t, state);
            if (hff < 0) goto oom;
            for (int k = 0; k < nops; k++) helpful[k] = hff != COST_INF && t->op_mark[ops[k]] == t->epoch;
        }
        for (int k = 0; k < nops; k++) {
            apply_op(t, st->states + (size_t)s * (size_t)st->nwords, ops[k], child);
            long c = meet(st, child, s, ops[k], g + 1, &added);
            if (c < 0) goto done;
            if (!added) continue;
            dead = guide_evaluate(gd, t, child, ACCEPTED(st, c), h);
            if (dead < 0) goto done;
            st->h[c] = h[0];
            out->generated++;
            if (!dead && guide_push(gd, h, ++counter, 0, (int)c, helpful[k])) goto oom;
        }
    }
    status = 0;
    goto done;
oom:
    PyErr_NoMemory();
done:
    free(helpful);
    free(closed);
    return status;
}

/* The landmarks operator `o` makes true that the path to state `s` has not yet accepted (0 where the landmark
   count does not guide the search): how much nearer the goal the count will find its successor, as far as the
   operator's own effects tell. A lazy search's successors all wait under their parent's value, so in the count's
   lists those reaching more new landmarks go first, where first generated would go first otherwise: on maintenance
   (IPC 2014), where any order of the days' choices is a plan's and a wrong one a dead end, the first-listed
   choices ran into dead ends for seconds. */
static int landmarks_reached(const TaskObject *t, const Store *st, long s, int o) {
    if (!st->landmarks) return 0;
    const word *add = W(t, t->add, o), *accepted = ACCEPTED(st, s);
    int count = 0;
    for (int i = 0; i < t->nwords; i++) count += __builtin_popcountll(add[i] & st->landmarks[i] & ~accepted[i]);
    return count;
}

/* Lazy greedy best-first (deferred evaluation; Richter & Helmert 2009, Fast Downward's lazy_greedy): a state's
   successors wait in the open lists as (state, operator) under the state's own h, and each is made, evaluated and
   expanded only when it is taken and new. So h is computed once per state expanded, not once per state
   generated, which pays where states have many successors. Goal test on expansion. */
static int run_lazy(TaskObject *t, Store *st, Guide *gd, word *child, int *ops, Outcome *out) {
    int added, status = -1, h[MAX_HEURISTICS];
    int64_t counter = 0;
    int *edge_parent = NULL, *edge_op = NULL; /* the waiting successors: (state, operator) */
    size_t nedges = 0, room = 0, nw = (size_t)st->nwords;
    long s = 0; /* the state to expand: the initial state first */
    for (;;) {
        const word *state = st->states + (size_t)s * nw;
        int stop = expanding(t, state, s, out);
        if (stop) {
            status = stop > 0 ? 0 : -1;
            goto done;
        }
        int dead = guide_evaluate(gd, t, state, ACCEPTED(st, s), h);
        if (dead < 0) goto done;
        st->h[s] = h[0];
        out->generated++;
        if (!dead) {
            int nops = applicable_ops(t, state, ops);
            if (nedges + (size_t)nops > room) {
                room = 2 * (nedges + (size_t)nops) + 1024;
                if (room > INT_MAX || grow((void **)&edge_parent, room * sizeof(int)) ||
                    grow((void **)&edge_op, room * sizeof(int)))
                    goto oom;
            }
            for (int k = 0; k < nops; k++, nedges++) {
                edge_parent[nedges] = (int)s;
                edge_op[nedges] = ops[k];
                if (guide_push(gd, h, ++counter, landmarks_reached(t, st, s, ops[k]), (int)nedges,
                               gd->helpful && t->op_mark[ops[k]] == t->epoch))
                    goto oom;
            }
        }
        for (added = 0; !added;) { /* the next waiting successor that is a new state */
            int q = guide_turn(gd);
            if (q < 0) {
                status = 0;
                goto done;
            }
            int e = heap_pop(&gd->lists[q]).item;
            long p = edge_parent[e];
            apply_op(t, st->states + (size_t)p * nw, edge_op[e], child);
            s = meet(st, child, p, edge_op[e], st->g[p] + 1, &added);
            if (s < 0) goto done;
        }
    }
oom:
    PyErr_NoMemory();
done:
    free(edge_parent);
    free(edge_op);
    return status;
}

/* -- Python glue ------------------------------------------------------------------------------------- */

/* The heuristic called `name` for task t; -1 with a ValueError for an unknown one, or LM-cut where the task has
   conditional effects. */
static int heuristic_id(const TaskObject *t, const char *name) {
    for (int i = 0; i < H_COUNT; i++) {
        if (strcmp(name, HEURISTIC_NAMES[i])) continue;
        if (i == H_LMCUT && t->ncond) {
            PyErr_Format(PyExc_ValueError, "lmcut does not take conditional effects (this task has %d): its cuts "
                                           "would no longer be admissible; hmax keeps A*'s plans optimal", t->ncond);
            return -1;
        }
        return i;
    }
    PyErr_Format(PyExc_ValueError, "unknown heuristic '%s'", name);
    return -1;
}

/* The heuristics named in `spec`, joined by '+' ("hff+lmcount"), into the guide of a greedy search; -1 with a
   ValueError for an unknown or repeated name, or more than one for another search. */
static int read_guide(const TaskObject *t, const char *spec, int greedy, Guide *gd) {
    char name[32];
    for (const char *at = spec;; at++) {
        size_t length = strcspn(at, "+");
        if (gd->n == MAX_HEURISTICS) {
            PyErr_Format(PyExc_ValueError, "at most %d heuristics take turns: '%s'", MAX_HEURISTICS, spec);
            return -1;
        }
        size_t copied = length < sizeof(name) ? length : sizeof(name) - 1; /* no heuristic has so long a name */
        memcpy(name, at, copied);
        name[copied] = 0;
        int h = heuristic_id(t, name);
        if (h < 0) return -1;
        if (h == H_LMCOUNT && !greedy) {
            PyErr_Format(PyExc_ValueError, "lmcount counts the landmarks not yet reached on a path: it guides the "
                                           "greedy searches (gbfs, lazy) only");
            return -1;
        }
        for (int i = 0; i < gd->n; i++)
            if (gd->heuristics[i] == h) {
                PyErr_Format(PyExc_ValueError, "heuristic '%s' named twice in '%s'", name, spec);
                return -1;
            }
        gd->heuristics[gd->n] = h;
        gd->best[gd->n++] = COST_INF;
        gd->helpful |= h == H_HFF;
        at += length;
        if (!*at) break;
    }
    if (gd->n > 1 && !greedy) {
        PyErr_Format(PyExc_ValueError, "heuristics take turns only in greedy searches (gbfs, lazy), not with '%s'", spec);
        return -1;
    }
    return 0;
}

static PyObject *Task_search(TaskObject *t, PyObject *args) {
    const char *search, *heuristic_name;
    double seconds = 0.0;
    if (!PyArg_ParseTuple(args, "ss|d", &search, &heuristic_name, &seconds)) return NULL;
    if (!(seconds >= 0.0)) return PyErr_Format(PyExc_ValueError, "a search's time must be 0 (no limit) or more seconds");
    SearchKind kind;
    if (!strcmp(search, "bfs")) kind = S_BFS;
    else if (!strcmp(search, "astar")) kind = S_ASTAR;
    else if (!strcmp(search, "gbfs")) kind = S_GBFS;
    else if (!strcmp(search, "lazy")) kind = S_LAZY;
    else return PyErr_Format(PyExc_ValueError, "unknown search %R", PyTuple_GET_ITEM(args, 0));
    Guide guide = {0};
    if (read_guide(t, heuristic_name, kind == S_GBFS || kind == S_LAZY, &guide)) return NULL;
    int heuristic = guide.heuristics[0];

    Store st;
    Outcome out = {-1, 0, 0, seconds > 0.0 ? monotonic_seconds() + seconds : 0.0, 0};
    word *child = malloc(sizeof(word) * (size_t)t->nwords);
    int *ops = malloc(sizeof(int) * (size_t)(t->nops ? t->nops : 1)), added, status = -1;
    PyObject *result = NULL;
    if (store_init(&st, t->nwords) || !child || !ops) {
        PyErr_NoMemory();
        goto done;
    }
    for (int i = 0; i < guide.n && kind != S_ASTAR; i++)
        if (guide.heuristics[i] == H_LMCOUNT) { /* the path-dependent landmark count keeps its accepted sets */
            if (find_landmarks(t)) {
                PyErr_NoMemory();
                goto done;
            }
            st.landmarks = t->landmarks;
        }
    if (kind == S_BFS && !t->unit) kind = S_ASTAR, heuristic = H_BLIND; /* uniform-cost search */
    if (meet(&st, t->init, -1, -1, 0, &added) < 0) goto done;
    if (kind == S_BFS && goal_reached(t, t->init)) {
        out.goal_state = 0;
        status = 0;
    } else if (kind == S_BFS) {
        status = run_bfs(t, &st, ops, &out);
    } else {
        status = kind == S_ASTAR ? run_astar(t, &st, heuristic, child, ops, &out)
                 : kind == S_GBFS ? run_greedy(t, &st, &guide, child, ops, &out)
                                  : run_lazy(t, &st, &guide, child, ops, &out);
    }
    if (status) goto done;
    PyObject *plan = Py_None;
    Py_INCREF(plan);
    if (out.goal_state >= 0) {
        Py_ssize_t length = 0;
        for (long s = out.goal_state; st.parent[s] >= 0; s = st.parent[s]) length++;
        Py_DECREF(plan);
        if (!(plan = PyList_New(length))) goto done;
        for (long s = out.goal_state; st.parent[s] >= 0; s = st.parent[s])
            PyList_SET_ITEM(plan, --length, PyLong_FromLong(st.op[s]));
    }
    result = Py_BuildValue("(NllO)", plan, out.expanded, out.generated, out.timed_out ? Py_True : Py_False);
done:
    guide_free(&guide);
    store_free(&st);
    free(child);
    free(ops);
    return result;
}

static PyObject *Task_heuristic(TaskObject *t, PyObject *args) {
    const char *name;
    PyObject *state, *passed = NULL;
    if (!PyArg_ParseTuple(args, "sO|O", &name, &state, &passed)) return NULL;
    if (passed == Py_None) passed = NULL;
    int heuristic = heuristic_id(t, name);
    if (heuristic < 0) return NULL;
    word *s = malloc(sizeof(word) * (size_t)t->nwords), *accepted = malloc(sizeof(word) * (size_t)t->nwords);
    PyObject *result = NULL;
    if (!s || !accepted) PyErr_NoMemory();
    else if (!int_to_words(state, s, t->nwords, "state") && !(passed && int_to_words(passed, accepted, t->nwords, "passed"))) {
        if (passed && find_landmarks(t)) {
            PyErr_NoMemory();
        } else {
            for (int i = 0; passed && i < t->nwords; i++) accepted[i] = (accepted[i] | s[i]) & t->landmarks[i];
            int h = evaluate(t, heuristic, s, passed ? accepted : NULL);
            if (h >= 0) result = PyFloat_FromDouble(h == COST_INF ? Py_HUGE_VAL : (double)h);
        }
    }
    free(s);
    free(accepted);
    return result;
}

static PyObject *Task_successors(TaskObject *t, PyObject *state) {
    PyObject *result = NULL;
    word *s = malloc(sizeof(word) * (size_t)t->nwords), *child = malloc(sizeof(word) * (size_t)t->nwords);
    int *ops = malloc(sizeof(int) * (size_t)(t->nops ? t->nops : 1));
    if (!s || !child || !ops) PyErr_NoMemory();
    else if (!int_to_words(state, s, t->nwords, "state")) {
        int n = applicable_ops(t, s, ops);
        result = PyList_New(n);
        for (int k = 0; result && k < n; k++) {
            apply_op(t, s, ops[k], child);
            PyObject *pair = Py_BuildValue("(Ni)", words_to_int(child, t->nwords), ops[k]);
            if (!pair) Py_CLEAR(result);
            else PyList_SET_ITEM(result, k, pair);
        }
    }
    free(s);
    free(child);
    free(ops);
    return result;
}

static void Task_dealloc(TaskObject *t) {
    free(t->pre);
    free(t->neg);
    free(t->add);
    free(t->keep);
    free(t->cond_start);
    free(t->cond_op);
    free(t->cpre);
    free(t->cneg);
    free(t->cadd);
    free(t->cdel);
    free(t->neg_of);
    free(t->neg_index);
    free(t->ax_layer);
    free(t->ax_head);
    free(t->ax_pos);
    free(t->ax_neg);
    free(t->derived);
    free(t->init);
    free(t->goal);
    free(t->goal_neg);
    free(t->free_ops);
    rows_free(&t->filed);
    rows_free(&t->rpre);
    rows_free(&t->radd);
    rows_free(&t->consumers);
    rows_free(&t->achievers);
    free(t->fact_cost);
    free(t->achiever);
    free(t->missing);
    free(t->supporter);
    free(t->op_max);
    free(t->base_cost);
    free(t->cost);
    free(t->mark);
    free(t->in_zone);
    free(t->op_mark);
    free(t->stack);
    free(t->cut);
    free(t->heap.a);
    free(t->landmarks);
    free(t->lm_fact);
    free(t->lm_needs);
    Py_TYPE(t)->tp_free((PyObject *)t);
}

/* The indices of the set bits of mask `m`, lowest first, into `out`; returns how many. */
static int set_bits(const TaskObject *t, const word *m, int *out) {
    int n = 0;
    for (int i = 0; i < t->nwords; i++)
        for (word rest = m[i]; rest; rest &= rest - 1) out[n++] = i * 64 + __builtin_ctzll(rest);
    return n;
}

/* Relaxed operator r's preconditions (`which` 0) or adds (1) as relaxed facts into `out` (room for nrf): an
   operator's own, or a conditional effect's (its operator's precondition and its condition; its adds), each with
   the negated facts of what it asks false (preconditions) or deletes (adds); the goal operator's (nrel) the goal's.
   Returns how many. */
static int relaxed_facts(const TaskObject *t, int r, int which, int *out) {
    const word *pos, *neg, *also_pos = NULL, *also_neg = NULL;
    if (r == t->nrel) pos = t->goal, neg = t->goal_neg;
    else if (r < t->nops) pos = W(t, which ? t->add : t->pre, r), neg = which ? NULL : W(t, t->neg, r);
    else if (r >= t->nops + t->ncond) { /* a rule: its body, its head */
        int a = r - t->nops - t->ncond;
        if (which) {
            out[0] = t->ax_head[a];
            return 1;
        }
        pos = W(t, t->ax_pos, a), neg = W(t, t->ax_neg, a);
    } else {
        int c = r - t->nops, o = t->cond_op[c];
        pos = W(t, which ? t->cadd : t->cpre, c), neg = W(t, which ? t->cdel : t->cneg, c);
        if (!which) also_pos = W(t, t->pre, o), also_neg = W(t, t->neg, o);
    }
    int n = 0;
    for (int i = 0; i < t->nwords; i++) {
        word yes = pos[i] | (also_pos ? also_pos[i] : 0);
        word no = r < t->nops && which ? ~W(t, t->keep, r)[i] : (neg ? neg[i] : 0) | (also_neg ? also_neg[i] : 0);
        for (word rest = yes; rest; rest &= rest - 1) out[n++] = i * 64 + __builtin_ctzll(rest);
        for (word rest = no; rest; rest &= rest - 1) {
            int f = i * 64 + __builtin_ctzll(rest);
            if (f < t->nfacts && t->neg_index[f] >= 0) out[n++] = t->nfacts + t->neg_index[f];
        }
    }
    return n;
}

/* The negated facts: one per fact (not derived) that an operator's precondition, a conditional effect's condition, a
   rule's body or the goal asks false; -1 when out of memory. */
static int find_negations(TaskObject *t) {
    word *asked = calloc((size_t)t->nwords, sizeof(word));
    t->neg_index = malloc(sizeof(int) * ((size_t)t->nfacts + 1));
    t->neg_of = malloc(sizeof(int) * ((size_t)t->nfacts + 1));
    if (!asked || !t->neg_index || !t->neg_of) {
        free(asked);
        return -1;
    }
    for (int i = 0; i < t->nwords; i++) {
        asked[i] = t->goal_neg[i];
        for (int o = 0; o < t->nops; o++) asked[i] |= W(t, t->neg, o)[i];
        for (int c = 0; c < t->ncond; c++) asked[i] |= W(t, t->cneg, c)[i];
        for (int a = 0; a < t->nax; a++) asked[i] |= W(t, t->ax_neg, a)[i];
        asked[i] &= ~t->derived[i]; /* a derived fact asked false: left out of the relaxation */
    }
    t->nneg = 0;
    for (int f = 0; f < t->nfacts; f++) {
        t->neg_index[f] = in_state(asked, f) ? t->nneg : -1;
        if (t->neg_index[f] >= 0) t->neg_of[t->nneg++] = f;
    }
    t->nrf = t->nfacts + t->nneg;
    free(asked);
    return 0;
}

/* The operator index structures: the successor filing and the relaxed task. */
static int build_indexes(TaskObject *t) {
    if (find_negations(t)) return -1;
    int nf = t->nrf + 2, nr = t->nrel + 1, goal = t->nrf, truth = t->nrf + 1, status = -1;
    int *facts = malloc(sizeof(int) * (size_t)nf), *row = NULL, *item = NULL, *uses = calloc((size_t)nf, sizeof(int));
    t->free_ops = malloc(sizeof(int) * (size_t)(t->nops + 1));
    if (!facts || !uses || !t->free_ops) goto done;
    size_t room = (size_t)t->nfacts + (size_t)nr + 1, npre = 0, nadd = 0;
    for (int o = 0; o < nr; o++) {
        npre += (size_t)relaxed_facts(t, o, 0, facts) + 1;
        if (o < t->nrel) nadd += (size_t)relaxed_facts(t, o, 1, facts);
    }
    room += npre > nadd ? npre : nadd;
    row = malloc(sizeof(int) * room), item = malloc(sizeof(int) * room);
    if (!row || !item) goto done;

    /* successor filing: each operator under its precondition that the fewest operators need (the first
       such) */
    for (int o = 0; o < t->nops; o++)
        for (int k = 0, n = set_bits(t, W(t, t->pre, o), facts); k < n; k++) uses[facts[k]]++;
    int nfiled = 0;
    t->nfree = 0;
    for (int o = 0; o < t->nops; o++) {
        int best = -1;
        for (int k = 0, n = set_bits(t, W(t, t->pre, o), facts); k < n; k++)
            if (best < 0 || uses[facts[k]] < uses[best]) best = facts[k];
        if (best < 0) t->free_ops[t->nfree++] = o;
        else row[nfiled] = best, item[nfiled++] = o;
    }
    if (rows_build(&t->filed, t->nfacts, row, item, nfiled)) goto done;

    /* relaxed preconditions (TRUE for none; the goal operator needs the goal facts) and their inverse */
    int n = 0;
    for (int o = 0; o < nr; o++) {
        int count = relaxed_facts(t, o, 0, facts);
        for (int k = 0; k < count; k++) row[n] = o, item[n++] = facts[k];
        if (!count) row[n] = o, item[n++] = truth;
    }
    if (rows_build(&t->rpre, nr, row, item, n) || rows_build(&t->consumers, nf, item, row, n)) goto done;
    n = 0;
    for (int o = 0; o < t->nrel; o++)
        for (int k = 0, count = relaxed_facts(t, o, 1, facts); k < count; k++) row[n] = o, item[n++] = facts[k];
    row[n] = t->nrel, item[n++] = goal;
    if (rows_build(&t->radd, nr, row, item, n) || rows_build(&t->achievers, nf, item, row, n)) goto done;

    size_t stack_room = (size_t)nf + (size_t)nr;
    t->fact_cost = malloc(sizeof(int) * (size_t)nf);
    t->achiever = malloc(sizeof(int) * (size_t)nf);
    t->missing = malloc(sizeof(int) * (size_t)nr);
    t->supporter = malloc(sizeof(int) * (size_t)nr);
    t->op_max = malloc(sizeof(int) * (size_t)nr);
    t->base_cost = malloc(sizeof(int) * (size_t)nr);
    t->cost = malloc(sizeof(int) * (size_t)nr);
    t->mark = calloc((size_t)nf, sizeof(int));
    t->in_zone = calloc((size_t)nf, sizeof(int));
    t->op_mark = calloc((size_t)nr, sizeof(int));
    t->stack = malloc(sizeof(int) * stack_room);
    t->cut = malloc(sizeof(int) * (size_t)nr);
    if (!t->fact_cost || !t->achiever || !t->missing || !t->supporter || !t->op_max || !t->base_cost || !t->cost || !t->mark ||
        !t->in_zone || !t->op_mark || !t->stack || !t->cut)
        goto done;
    status = 0;
done:
    free(row);
    free(item);
    free(uses);
    free(facts);
    return status;
}

static const char *const MASK_NAMES[4] = {"pre", "pre_neg", "add", "delete"};
static PyObject *mask_names[4]; /* the same, interned at import */

/* The operators' costs: each 1 where `costs` is None, else its items (non-negative ints); the goal operator's 0. */
static int read_costs(TaskObject *t, PyObject *costs) {
    PyObject *seq = costs == Py_None ? NULL : PySequence_Fast(costs, "costs must be None or a sequence of ints");
    if (costs != Py_None && !seq) return -1;
    if (seq && PySequence_Fast_GET_SIZE(seq) != t->nops) {
        PyErr_Format(PyExc_ValueError, "costs: %zd for %d operators", PySequence_Fast_GET_SIZE(seq), t->nops);
        Py_DECREF(seq);
        return -1;
    }
    t->unit = 1;
    t->min_cost = 1;
    for (int o = 0; o < t->nops; o++) {
        long cost = seq ? PyLong_AsLong(PySequence_Fast_GET_ITEM(seq, o)) : 1;
        if (cost == -1 && PyErr_Occurred()) break;
        if (cost < 0 || cost > INT_MAX / 4) {
            PyErr_Format(PyExc_ValueError, "operator %d costs %ld: costs are ints from 0 to %d", o, cost, INT_MAX / 4);
            break;
        }
        t->base_cost[o] = (int)cost;
        t->unit &= cost == 1;
        if (o == 0 || cost < t->min_cost) t->min_cost = (int)cost;
    }
    for (int c = 0; c < t->ncond; c++) t->base_cost[t->nops + c] = t->base_cost[t->cond_op[c]];
    for (int a = 0; a < t->nax; a++) t->base_cost[t->nops + t->ncond + a] = 0;
    t->base_cost[t->nrel] = 0;
    t->unit &= !t->nax; /* rules cost 0: the unit-cost sweep would not meet facts in order of cost */
    Py_XDECREF(seq);
    return PyErr_Occurred() ? -1 : 0;
}

static PyObject *effects_name; /* "effects", interned at import */

/* The derived predicates' rules, each (layer, head mask, pos, neg), in ascending layers, and the derived facts'
   mask (NULL: none); -1 with an exception set. */
static int read_axioms(TaskObject *t, PyObject *axioms, PyObject *derived) {
    size_t nw = (size_t)t->nwords;
    PyObject *seq = axioms ? PySequence_Fast(axioms, "axioms must be a sequence of (layer, head, pos, neg)") : NULL;
    if (axioms && !seq) return -1;
    Py_ssize_t n = seq ? PySequence_Fast_GET_SIZE(seq) : 0;
    int status = -1;
    t->nax = (int)n;
    t->ax_layer = malloc(sizeof(int) * ((size_t)n + 1));
    t->ax_head = malloc(sizeof(int) * ((size_t)n + 1));
    t->ax_pos = malloc(sizeof(word) * ((size_t)n * nw + 1));
    t->ax_neg = malloc(sizeof(word) * ((size_t)n * nw + 1));
    t->derived = calloc(nw, sizeof(word));
    word *head = malloc(sizeof(word) * nw);
    if (!t->ax_layer || !t->ax_head || !t->ax_pos || !t->ax_neg || !t->derived || !head) {
        PyErr_NoMemory();
        goto done;
    }
    if (derived && int_to_words(derived, t->derived, t->nwords, "derived")) goto done;
    for (Py_ssize_t a = 0; a < n; a++) {
        PyObject *rule = PySequence_Fast(PySequence_Fast_GET_ITEM(seq, a), "a rule must be (layer, head, pos, neg)");
        if (!rule) goto done;
        int bad = PySequence_Fast_GET_SIZE(rule) != 4;
        long layer = bad ? 0 : PyLong_AsLong(PySequence_Fast_GET_ITEM(rule, 0));
        bad = bad || (layer == -1 && PyErr_Occurred()) ||
              int_to_words(PySequence_Fast_GET_ITEM(rule, 1), head, t->nwords, "head") ||
              int_to_words(PySequence_Fast_GET_ITEM(rule, 2), W(t, t->ax_pos, a), t->nwords, "pos") ||
              int_to_words(PySequence_Fast_GET_ITEM(rule, 3), W(t, t->ax_neg, a), t->nwords, "neg");
        Py_DECREF(rule);
        int h = -1;
        for (int i = 0; !bad && i < t->nwords && h < 0; i++)
            if (head[i]) h = i * 64 + __builtin_ctzll(head[i]);
        if (!bad && (h < 0 || layer < 0 || (a && layer < t->ax_layer[a - 1]))) {
            PyErr_SetString(PyExc_ValueError, "a rule is (layer, head, pos, neg): one head fact, layers ascending");
            bad = 1;
        }
        if (bad) goto done;
        t->ax_layer[a] = (int)layer;
        t->ax_head[a] = h;
    }
    status = 0;
done:
    free(head);
    Py_XDECREF(seq);
    return status;
}

/* Each operator's conditional effects: its `effects` attribute, a sequence of (pre, pre_neg, add, delete) masks (an
   operator without the attribute has none). Sets ncond, nrel and the effect arrays; -1 with an exception set. */
static int read_effects(TaskObject *t, PyObject *ops) {
    PyObject **lists = calloc((size_t)t->nops + 1, sizeof(PyObject *));
    t->cond_start = malloc(sizeof(int) * ((size_t)t->nops + 1));
    int status = -1;
    if (!lists || !t->cond_start) {
        PyErr_NoMemory();
        goto done;
    }
    long total = 0;
    for (int o = 0; o < t->nops; o++) {
        t->cond_start[o] = (int)total;
        PyObject *effects = PyObject_GetAttr(PySequence_Fast_GET_ITEM(ops, o), effects_name);
        if (!effects) {
            if (!PyErr_ExceptionMatches(PyExc_AttributeError)) goto done;
            PyErr_Clear();
            continue;
        }
        lists[o] = PySequence_Fast(effects, "an operator's effects must be a sequence of (pre, pre_neg, add, delete)");
        Py_DECREF(effects);
        if (!lists[o]) goto done;
        total += PySequence_Fast_GET_SIZE(lists[o]);
        if (total >= INT_MAX / 4) {
            PyErr_SetString(PyExc_ValueError, "too many conditional effects");
            goto done;
        }
    }
    t->cond_start[t->nops] = (int)total;
    t->ncond = (int)total;
    t->nrel = t->nops + t->ncond + t->nax;
    size_t room = (size_t)total * (size_t)t->nwords + 1;
    t->cond_op = malloc(sizeof(int) * ((size_t)total + 1));
    t->cpre = malloc(sizeof(word) * room);
    t->cneg = malloc(sizeof(word) * room);
    t->cadd = malloc(sizeof(word) * room);
    t->cdel = malloc(sizeof(word) * room);
    if (!t->cond_op || !t->cpre || !t->cneg || !t->cadd || !t->cdel) {
        PyErr_NoMemory();
        goto done;
    }
    for (int o = 0; o < t->nops; o++) {
        for (int c = t->cond_start[o]; c < t->cond_start[o + 1]; c++) {
            PyObject *effect = PySequence_Fast_GET_ITEM(lists[o], c - t->cond_start[o]);
            word *into[4] = {W(t, t->cpre, c), W(t, t->cneg, c), W(t, t->cadd, c), W(t, t->cdel, c)};
            PyObject *masks = PySequence_Fast(effect, "a conditional effect must be (pre, pre_neg, add, delete)");
            if (!masks) goto done;
            int failed = PySequence_Fast_GET_SIZE(masks) != 4;
            if (failed) PyErr_SetString(PyExc_ValueError, "a conditional effect must be (pre, pre_neg, add, delete)");
            for (int m = 0; m < 4 && !failed; m++)
                failed = int_to_words(PySequence_Fast_GET_ITEM(masks, m), into[m], t->nwords, MASK_NAMES[m]) != 0;
            Py_DECREF(masks);
            if (failed) goto done;
            t->cond_op[c] = o;
        }
    }
    status = 0;
done:
    if (lists)
        for (int o = 0; o < t->nops; o++) Py_XDECREF(lists[o]);
    free(lists);
    return status;
}

static PyObject *Task_new(PyTypeObject *type, PyObject *args, PyObject *kwargs) {
    static char *keywords[] = {"nfacts", "operators", "init", "goal", "goal_neg", "costs", "axioms", "derived", NULL};
    int nfacts;
    PyObject *operators, *init, *goal, *goal_neg, *costs = Py_None, *axioms = NULL, *derived = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "iOOOO|OOO", keywords, &nfacts, &operators, &init, &goal, &goal_neg,
                                     &costs, &axioms, &derived))
        return NULL;
    if (nfacts < 0) return PyErr_Format(PyExc_ValueError, "nfacts must not be negative");
    PyObject *seq = PySequence_Fast(operators, "operators must be a sequence");
    if (!seq) return NULL;
    TaskObject *t = (TaskObject *)type->tp_alloc(type, 0);
    if (!t) goto fail;
    t->nfacts = nfacts;
    t->nwords = nfacts > 0 ? (nfacts + 63) / 64 : 1;
    if (PySequence_Fast_GET_SIZE(seq) >= INT_MAX / 2) {
        PyErr_SetString(PyExc_ValueError, "too many operators");
        goto fail;
    }
    t->nops = (int)PySequence_Fast_GET_SIZE(seq);
    size_t nw = (size_t)t->nwords, total = (size_t)t->nops * nw + 1;
    t->pre = malloc(sizeof(word) * total);
    t->neg = malloc(sizeof(word) * total);
    t->add = malloc(sizeof(word) * total);
    t->keep = malloc(sizeof(word) * total);
    t->init = malloc(sizeof(word) * nw);
    t->goal = malloc(sizeof(word) * nw);
    t->goal_neg = malloc(sizeof(word) * nw);
    if (!t->pre || !t->neg || !t->add || !t->keep || !t->init || !t->goal || !t->goal_neg) {
        PyErr_NoMemory();
        goto fail;
    }
    if (int_to_words(init, t->init, t->nwords, "init") || int_to_words(goal, t->goal, t->nwords, "goal") ||
        int_to_words(goal_neg, t->goal_neg, t->nwords, "goal_neg"))
        goto fail;
    for (int o = 0; o < t->nops; o++) {
        word *into[4] = {W(t, t->pre, o), W(t, t->neg, o), W(t, t->add, o), W(t, t->keep, o)};
        for (int m = 0; m < 4; m++) {
            PyObject *mask = PyObject_GetAttr(PySequence_Fast_GET_ITEM(seq, o), mask_names[m]);
            int failed = !mask || int_to_words(mask, into[m], t->nwords, MASK_NAMES[m]);
            Py_XDECREF(mask);
            if (failed) goto fail;
        }
        for (size_t i = 0; i < nw; i++) into[3][i] = ~into[3][i];
    }
    if (read_axioms(t, axioms, derived) || read_effects(t, seq)) goto fail;
    if (build_indexes(t)) {
        PyErr_NoMemory();
        goto fail;
    }
    if (read_costs(t, costs)) goto fail;
    Py_DECREF(seq);
    return (PyObject *)t;
fail:
    Py_DECREF(seq);
    Py_XDECREF(t);
    return NULL;
}

static PyMethodDef Task_methods[] = {
    {"search", (PyCFunction)Task_search, METH_VARARGS,
     "search(search, heuristic, seconds=0.0) -> (plan as operator indices or None, expanded, generated, whether "
     "its time ran out first)"},
    {"heuristic", (PyCFunction)Task_heuristic, METH_VARARGS,
     "heuristic(name, state, passed=None) -> h (inf for a dead end); passed: the facts true in some earlier state of "
     "the path to state, which the landmark count reads (None: state is the path's only state)"},
    {"successors", (PyCFunction)Task_successors, METH_O,
     "successors(state) -> [(child state, operator index)] in generation order"},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject TaskType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "strips_planner._core.Task",
    .tp_doc = "Task(nfacts, operators, init, goal, goal_neg, costs=None): a grounded task. States and masks are "
              "int bitsets over the facts; each operator has the masks pre, pre_neg, add and delete, and may have "
              "effects: conditional effects, each (pre, pre_neg, add, delete); costs: one non-negative int per "
              "operator (None: each costs 1).",
    .tp_basicsize = sizeof(TaskObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_new = Task_new,
    .tp_dealloc = (destructor)Task_dealloc,
    .tp_methods = Task_methods,
};

static struct PyModuleDef core_module = {
    PyModuleDef_HEAD_INIT,
    .m_name = "_core",
    .m_doc = "Searches and relaxation heuristics over grounded STRIPS tasks.",
    .m_size = -1,
};

PyMODINIT_FUNC PyInit__core(void) {
    for (int m = 0; m < 4; m++)
        if (!mask_names[m] && !(mask_names[m] = PyUnicode_InternFromString(MASK_NAMES[m]))) return NULL;
    if (!effects_name && !(effects_name = PyUnicode_InternFromString("effects"))) return NULL;
    if (PyType_Ready(&TaskType) < 0) return NULL;
    PyObject *module = PyModule_Create(&core_module);
    if (!module) return NULL;
    Py_INCREF(&TaskType);
    if (PyModule_AddObject(module, "Task", (PyObject *)&TaskType) < 0) {
        Py_DECREF(&TaskType);
        Py_DECREF(module);
        return NULL;
    }
    return module;
}
