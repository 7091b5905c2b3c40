/* What grounding's C modules (_explore, _ground) share: atoms as int keys under an open-addressing hash table,
 * sorted by key, and ints read from Python sequences. Functions are static inline, as in _support.h. */
#ifndef SEMGOAL_PLANNER_ATOMS_H
#define SEMGOAL_PLANNER_ATOMS_H

#include "_support.h"

#include <limits.h>

/* -- atoms: their keys under an open-addressing hash table --------------------------------------------- */

typedef struct {
    int width;
    int *keys; /* natoms x width */
    int natoms, room;
    int *slots;  /* an atom's index + 1; 0 marks an empty slot */
    size_t mask; /* the number of slots (a power of two) - 1 */
} Atoms;

#define KEY(a, i) ((a)->keys + (size_t)(i) * (size_t)(a)->width)

static inline size_t key_hash(const int *key, int width) {
    uint64_t h = 14695981039346656037ULL; /* FNV-1a over the ints */
    for (int i = 0; i < width; i++) h = (h ^ (uint32_t)key[i]) * 1099511628211ULL;
    return (size_t)(h ^ (h >> 32));
}

/* The slot holding `key`, or the empty slot where it would go. */
static inline size_t atoms_slot(const Atoms *a, const int *key) {
    size_t i = key_hash(key, a->width) & a->mask;
    while (a->slots[i] && memcmp(KEY(a, a->slots[i] - 1), key, sizeof(int) * (size_t)a->width))
        i = (i + 1) & a->mask;
    return i;
}

static inline int atoms_init(Atoms *a, int width) {
    a->width = width;
    a->natoms = 0;
    a->room = 64;
    a->mask = 127;
    a->keys = malloc(sizeof(int) * (size_t)a->room * (size_t)width);
    a->slots = calloc(a->mask + 1, sizeof(int));
    return a->keys && a->slots ? 0 : -1;
}

static inline void atoms_free(Atoms *a) {
    free(a->keys);
    free(a->slots);
}

/* The index of `key`, which is added if new; -1 when memory runs out. */
static inline int atoms_add(Atoms *a, const int *key) {
    size_t i = atoms_slot(a, key);
    if (a->slots[i]) return a->slots[i] - 1;
    if (a->natoms == a->room) {
        int *keys = realloc(a->keys, sizeof(int) * 2 * (size_t)a->room * (size_t)a->width);
        if (!keys) return -1;
        a->keys = keys;
        a->room *= 2;
    }
    memcpy(KEY(a, a->natoms), key, sizeof(int) * (size_t)a->width);
    if (2 * (size_t)(a->natoms + 1) > a->mask + 1) { /* keep the table at most half full */
        int *slots = calloc(2 * (a->mask + 1), sizeof(int));
        if (!slots) return -1;
        free(a->slots);
        a->slots = slots;
        a->mask = 2 * a->mask + 1;
        for (int k = 0; k < a->natoms; k++) a->slots[atoms_slot(a, KEY(a, k))] = k + 1;
        i = atoms_slot(a, key);
    }
    a->slots[i] = ++a->natoms;
    return a->natoms - 1;
}

/* The index of `key`; -1 when absent. */
static inline int atoms_find(const Atoms *a, const int *key) { return a->slots[atoms_slot(a, key)] - 1; }

/* `order` (atom indices) sorted by key, lexicographically: a stable counting sort per column, last
   column first. `range` bounds the values (predicate and object indices). */
static inline int sort_by_key(const Atoms *a, int *order, int n, int range) {
    int *count = malloc(sizeof(int) * ((size_t)range + 2)), *sorted = malloc(sizeof(int) * (size_t)(n ? n : 1));
    if (!count || !sorted) {
        free(count);
        free(sorted);
        return -1;
    }
    for (int column = a->width - 1; column >= 0; column--) {
        memset(count, 0, sizeof(int) * ((size_t)range + 2));
        for (int k = 0; k < n; k++) count[KEY(a, order[k])[column] + 2]++; /* values from -1 */
        for (int v = 1; v < range + 2; v++) count[v] += count[v - 1];
        for (int k = 0; k < n; k++) sorted[count[KEY(a, order[k])[column] + 1]++] = order[k];
        memcpy(order, sorted, sizeof(int) * (size_t)n);
    }
    free(count);
    free(sorted);
    return 0;
}

/* `seq` (a sequence of ints, at most `room` of them) into `out`; its length, or -1 with an exception set. */
static inline int read_ints(PyObject *seq, int *out, int room, const char *what) {
    PyObject *fast = PySequence_Fast(seq, what);
    if (!fast) return -1;
    Py_ssize_t n = PySequence_Fast_GET_SIZE(fast);
    if (n > room) {
        PyErr_Format(PyExc_ValueError, "%s: %zd ints, at most %d expected", what, n, room);
        n = -1;
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        long value = PyLong_AsLong(PySequence_Fast_GET_ITEM(fast, i));
        if (value == -1 && PyErr_Occurred()) n = -1;
        else if (value < INT_MIN || value > INT_MAX) {
            PyErr_Format(PyExc_OverflowError, "%s: %ld is out of range", what, value);
            n = -1;
        } else out[i] = (int)value;
    }
    Py_DECREF(fast);
    return (int)n;
}

#endif
