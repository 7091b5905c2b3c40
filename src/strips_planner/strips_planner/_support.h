/* What the planner's C modules (_core, _ground, _reader) share: int rows, Python-int bitsets and named
 * tuples. Functions are static inline, so each module gets its own copy and exports nothing. */
#ifndef SEMGOAL_PLANNER_SUPPORT_H
#define SEMGOAL_PLANNER_SUPPORT_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef uint64_t word;

/* Rows of ints: row i is items[start[i] .. start[i + 1]). */
typedef struct {
    int *start;
    int *items;
} Rows;

static inline void rows_free(Rows *rows) {
    free(rows->start);
    free(rows->items);
}

/* Rows from (row, item) pairs, items kept in pair order within a row. */
static inline int rows_build(Rows *rows, int nrows, const int *row_of, const int *item_of, int npairs) {
    rows->start = calloc((size_t)nrows + 1, sizeof(int));
    rows->items = malloc(sizeof(int) * (size_t)(npairs ? npairs : 1));
    int *fill = malloc(sizeof(int) * (size_t)(nrows + 1));
    if (!rows->start || !rows->items || !fill) {
        free(fill);
        return -1;
    }
    for (int k = 0; k < npairs; k++) rows->start[row_of[k] + 1]++;
    for (int i = 0; i < nrows; i++) rows->start[i + 1] += rows->start[i];
    memcpy(fill, rows->start, sizeof(int) * (size_t)(nrows + 1));
    for (int k = 0; k < npairs; k++) rows->items[fill[row_of[k]]++] = item_of[k];
    free(fill);
    return 0;
}

/* A tuple of `type` (a tuple subclass, such as a named tuple) from `n` new references, which it takes
   over; NULL (all of them released) when one is NULL or memory runs out. */
static inline PyObject *tuple_of(PyTypeObject *type, int n, PyObject **items) {
    PyObject *tuple = NULL;
    for (int i = 0; i < n; i++)
        if (!items[i]) goto fail;
    if (!(tuple = type == &PyTuple_Type ? PyTuple_New(n) : type->tp_alloc(type, n))) goto fail;
    for (int i = 0; i < n; i++) PyTuple_SET_ITEM(tuple, i, items[i]);
    return tuple;
fail:
    for (int i = 0; i < n; i++) Py_XDECREF(items[i]);
    return NULL;
}

#if !PY_LITTLE_ENDIAN
#error "states are read from Python ints as little-endian words"
#endif

/* A non-negative int as `nwords` little-endian words; an OverflowError for a negative int or one with
   bits beyond them. */
static inline int int_to_words(PyObject *value, word *out, int nwords, const char *what) {
    if (!PyLong_Check(value)) {
        PyErr_Format(PyExc_TypeError, "%s must be an int bitset, not %.100s", what, Py_TYPE(value)->tp_name);
        return -1;
    }
    size_t nbytes = sizeof(word) * (size_t)nwords;
#if PY_VERSION_HEX >= 0x030D0000
    Py_ssize_t needed = PyLong_AsNativeBytes(value, out, (Py_ssize_t)nbytes,
                                             Py_ASNATIVEBYTES_LITTLE_ENDIAN | Py_ASNATIVEBYTES_UNSIGNED_BUFFER |
                                                 Py_ASNATIVEBYTES_REJECT_NEGATIVE);
    if (needed < 0) return -1;
    if ((size_t)needed > nbytes) {
        PyErr_Format(PyExc_OverflowError, "%s has bits beyond the task's facts", what);
        return -1;
    }
    return 0;
#else
    return _PyLong_AsByteArray((PyLongObject *)value, (unsigned char *)out, nbytes, 1, 0);
#endif
}

static inline PyObject *words_to_int(const word *w, int nwords) {
#if PY_VERSION_HEX >= 0x030D0000
    return PyLong_FromUnsignedNativeBytes(w, sizeof(word) * (size_t)nwords, Py_ASNATIVEBYTES_LITTLE_ENDIAN);
#else
    return _PyLong_FromByteArray((const unsigned char *)w, sizeof(word) * (size_t)nwords, 1, 0);
#endif
}

#endif
