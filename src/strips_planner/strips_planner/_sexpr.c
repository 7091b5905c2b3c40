/* The PDDL reader's fast pass in C: ASCII text -> its single top-level s-expression as nested lists of
 * lower-case str tokens, or None.
 *
 * It reads exactly what strips_planner.pddl's regular-expression pass reads: a `;` comment runs to the end of
 * its line, `(` and `)` are tokens, a `?` starts a new token, and a name runs to whitespace (Python's
 * `str.isspace` over ASCII), a parenthesis, `?` or `;`. Names are interned, so the dictionary lookups that
 * follow (a domain's predicates looked up from its problem's atoms) compare pointers. None means "read this
 * in Python": non-ASCII text, or any structural error, which the Python reader then reports with its line
 * and column.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

/* ASCII whitespace as Python's str.isspace has it: \t \n \v \f \r, the separators 0x1c-0x1f and space. */
static int is_space(unsigned char c) { return (c >= 9 && c <= 13) || (c >= 28 && c <= 32); }

static int ends_name(unsigned char c) { return is_space(c) || c == '(' || c == ')' || c == '?' || c == ';'; }

/* The token text[start:end] in lower case, interned (a new reference). */
static PyObject *token(const char *text, Py_ssize_t start, Py_ssize_t end) {
    PyObject *fresh = PyUnicode_New(end - start, 127);
    if (!fresh) return NULL;
    Py_UCS1 *out = PyUnicode_1BYTE_DATA(fresh);
    for (Py_ssize_t i = start; i < end; i++) {
        unsigned char c = (unsigned char)text[i];
        out[i - start] = (Py_UCS1)(c >= 'A' && c <= 'Z' ? c + ('a' - 'A') : c);
    }
    PyUnicode_InternInPlace(&fresh);
    return fresh;
}

/* Appends `item` (a new reference, stolen) to the innermost open list; -1 on failure. */
static int append(PyObject *stack, PyObject *item) {
    Py_ssize_t depth = PyList_GET_SIZE(stack);
    int failed = PyList_Append(PyList_GET_ITEM(stack, depth - 1), item);
    Py_DECREF(item);
    return failed;
}

static PyObject *parse(PyObject *self, PyObject *arg) {
    (void)self;
    if (!PyUnicode_Check(arg)) {
        PyErr_SetString(PyExc_TypeError, "sexpr() takes a str");
        return NULL;
    }
    if (!PyUnicode_IS_ASCII(arg)) Py_RETURN_NONE;
    const char *text = (const char *)PyUnicode_1BYTE_DATA(arg);
    Py_ssize_t size = PyUnicode_GET_LENGTH(arg);
    PyObject *stack = PyList_New(0), *result = NULL;
    int structural = 0; /* a malformed text: None, so Python reads it again and says where */
    if (!stack) goto done;
    for (Py_ssize_t i = 0; i < size && !structural;) {
        unsigned char c = (unsigned char)text[i];
        if (is_space(c)) {
            i++;
        } else if (c == ';') {
            while (i < size && text[i] != '\n') i++;
        } else if (result) {
            structural = 1; /* a token after the end of the definition */
        } else if (c == '(') {
            PyObject *list = PyList_New(0);
            if (!list || PyList_Append(stack, list) < 0) {
                Py_XDECREF(list);
                goto done;
            }
            Py_DECREF(list);
            i++;
        } else if (c == ')') {
            Py_ssize_t depth = PyList_GET_SIZE(stack);
            if (depth == 0) {
                structural = 1;
                break;
            }
            PyObject *closed = PyList_GET_ITEM(stack, depth - 1);
            Py_INCREF(closed);
            if (PyList_SetSlice(stack, depth - 1, depth, NULL) < 0) {
                Py_DECREF(closed);
                goto done;
            }
            if (depth == 1) {
                result = closed;
            } else if (append(stack, closed) < 0) {
                goto done;
            }
            i++;
        } else if (PyList_GET_SIZE(stack) == 0) {
            structural = 1; /* a name outside any list */
        } else {
            Py_ssize_t start = i++;
            while (i < size && !ends_name((unsigned char)text[i])) i++;
            PyObject *name = token(text, start, i);
            if (!name || append(stack, name) < 0) goto done;
        }
    }
    if (structural || !result || PyList_GET_SIZE(stack) != 0) {
        Py_CLEAR(result);
        result = Py_NewRef(Py_None);
    }
done:
    Py_XDECREF(stack);
    if (PyErr_Occurred()) Py_CLEAR(result);
    return result;
}

static PyMethodDef sexpr_methods[] = {
    {"sexpr", parse, METH_O,
     "sexpr(text) -> the single top-level s-expression as nested lists of lower-case str, or None where the text "
     "is not ASCII or not well formed (the Python reader then says where)."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef sexpr_module = {
    PyModuleDef_HEAD_INIT, "_sexpr", "The PDDL reader's fast pass in C.", -1, sexpr_methods, NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__sexpr(void) { return PyModule_Create(&sexpr_module); }
