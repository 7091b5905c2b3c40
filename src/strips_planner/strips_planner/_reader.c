/* The PDDL reader's fast pass in C: ASCII text -> its single top-level s-expression as nested lists of
 * lower-case str tokens, or None; then each atom and literal of well-formed input checked against its
 * declaration and built (`atom`, `literal`, `conjunction`), or None.
 *
 * It reads exactly what strips_planner.pddl's regular-expression pass reads: a `;` comment runs to the end of
 * its line, `(` and `)` are tokens, a `?` starts a new token, and a name runs to whitespace (Python's
 * `str.isspace` over ASCII), a parenthesis, `?` or `;`. Names are interned, so the dictionary lookups that
 * follow (a domain's predicates looked up from its problem's atoms) compare pointers. None means "read this
 * in Python": non-ASCII text, or any structural error, which the Python reader then reports with its line
 * and column. The atoms' checks answer None likewise for anything that is not plainly valid (an unknown name,
 * a wrong count, a type that needs `either` or a warning), so strips_planner.pddl's own checks, the one place
 * that words every error, look at it again.
 */
#include "_support.h" /* Python.h, tuple_of */

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

/* -- atoms and literals ------------------------------------------------------------------------------------ */

/* Set once by `bind`: the reader's named tuples, the names no predicate may take, and the root type. */
static PyTypeObject *atom_type, *condition_type;
static PyObject *reserved, *root_type;

static PyObject *bind(PyObject *self, PyObject *args) {
    (void)self;
    PyObject *atom, *condition, *names, *root;
    if (!PyArg_ParseTuple(args, "O!O!O!U", &PyType_Type, &atom, &PyType_Type, &condition, &PyFrozenSet_Type,
                          &names, &root))
        return NULL;
    if (!PyType_IsSubtype((PyTypeObject *)atom, &PyTuple_Type) ||
        !PyType_IsSubtype((PyTypeObject *)condition, &PyTuple_Type))
        return PyErr_Format(PyExc_TypeError, "bind() takes two tuple types");
    Py_XSETREF(atom_type, (PyTypeObject *)Py_NewRef(atom));
    Py_XSETREF(condition_type, (PyTypeObject *)Py_NewRef(condition));
    Py_XSETREF(reserved, Py_NewRef(names));
    Py_XSETREF(root_type, Py_NewRef(root));
    Py_RETURN_NONE;
}

/* Whether an argument of type `has` may stand where `expected` is declared: 1, 0 (not plainly: None to the
   caller), -1 on error. `ancestors` maps each type to the set of it and its supertypes. */
static int fits(PyObject *has, PyObject *expected, PyObject *ancestors) {
    if (expected == root_type || has == expected) return 1;
    int same = PyObject_RichCompareBool(expected, root_type, Py_EQ);
    if (same) return same;
    if ((same = PyObject_RichCompareBool(has, expected, Py_EQ))) return same;
    PyObject *supertypes = PyDict_GetItemWithError(ancestors, has);
    if (!supertypes) return PyErr_Occurred() ? -1 : 0;
    return PySet_Contains(supertypes, expected);
}

/* What an atom's names are checked against: the predicates' argument types, the variables in scope (None in a
   problem), the objects and constants, each type's supertypes (`ancestors`), and whether a (not ...) is plain. */
typedef struct {
    PyObject *predicates, *variables, *objects, *ancestors;
    int negation;
} Scope;

/* `expr` as an Atom when it is plainly valid (a new reference), Py_None (borrowed) when Python should look,
   NULL on error. */
static PyObject *checked_atom(PyObject *expr, const Scope *in) {
    if (!atom_type) {
        PyErr_SetString(PyExc_RuntimeError, "_reader.bind() was not called");
        return NULL;
    }
    if (!PyList_CheckExact(expr) || PyList_GET_SIZE(expr) == 0) return Py_None;
    PyObject *head = PyList_GET_ITEM(expr, 0);
    if (!PyUnicode_CheckExact(head)) return Py_None;
    int special = PySet_Contains(reserved, head);
    if (special) return special < 0 ? NULL : Py_None;
    PyObject *expected = PyDict_GetItemWithError(in->predicates, head);
    Py_ssize_t nargs = PyList_GET_SIZE(expr) - 1;
    if (!expected) return PyErr_Occurred() ? NULL : Py_None;
    if (!PyTuple_CheckExact(expected) || PyTuple_GET_SIZE(expected) != nargs) return Py_None;
    for (Py_ssize_t i = 0; i < nargs; i++) {
        PyObject *arg = PyList_GET_ITEM(expr, i + 1);
        if (!PyUnicode_CheckExact(arg) || PyUnicode_GET_LENGTH(arg) == 0) return Py_None;
        PyObject *scope = PyUnicode_READ_CHAR(arg, 0) == '?' ? in->variables : in->objects;
        if (scope == Py_None) return Py_None;
        PyObject *has = PyDict_GetItemWithError(scope, arg);
        if (!has) return PyErr_Occurred() ? NULL : Py_None;
        int ok = fits(has, PyTuple_GET_ITEM(expected, i), in->ancestors);
        if (ok <= 0) return ok < 0 ? NULL : Py_None;
    }
    PyObject *items[2] = {Py_NewRef(head), PyList_GetSlice(expr, 1, nargs + 1)};
    if (items[1]) Py_SETREF(items[1], PyList_AsTuple(items[1]));
    return tuple_of(atom_type, 2, items);
}

static PyObject *atom(PyObject *self, PyObject *args) {
    (void)self;
    PyObject *expr;
    Scope in = {.variables = Py_None, .negation = 0};
    if (!PyArg_ParseTuple(args, "OO!O!O!", &expr, &PyDict_Type, &in.predicates, &PyDict_Type, &in.objects,
                          &PyDict_Type, &in.ancestors))
        return NULL;
    PyObject *result = checked_atom(expr, &in);
    return result == Py_None ? Py_NewRef(Py_None) : result;
}

/* `expr` as a Condition when it is a plainly valid atom or (with `negation`) a (not atom): a new reference,
   Py_None (borrowed) when Python should look, NULL on error. */
static PyObject *checked_literal(PyObject *expr, const Scope *in) {
    int positive = 1;
    if (PyList_CheckExact(expr) && PyList_GET_SIZE(expr) == 2) {
        PyObject *head = PyList_GET_ITEM(expr, 0);
        int is_not = PyUnicode_CheckExact(head) && PyUnicode_CompareWithASCIIString(head, "not") == 0;
        if (is_not && !in->negation) return Py_None;
        if (is_not) {
            positive = 0;
            expr = PyList_GET_ITEM(expr, 1);
        }
    }
    PyObject *found = checked_atom(expr, in);
    if (found == Py_None) return Py_None;
    PyObject *items[2] = {found, PyBool_FromLong(positive)};
    return tuple_of(condition_type, 2, items);
}

/* Appends to `out` the literals of `expr`: one literal, or an (and ...) of literals and of (and ...)s, whose empty
   parts () are skipped as the Python reader skips them. 1 when every one was plainly valid, 0 when one was not
   (Python should look), -1 on error. */
static int add_conjunction(PyObject *out, PyObject *expr, const Scope *in) {
    if (PyList_CheckExact(expr) && PyList_GET_SIZE(expr) > 0 && PyUnicode_CheckExact(PyList_GET_ITEM(expr, 0)) &&
        PyUnicode_CompareWithASCIIString(PyList_GET_ITEM(expr, 0), "and") == 0) {
        for (Py_ssize_t i = 1; i < PyList_GET_SIZE(expr); i++) {
            PyObject *part = PyList_GET_ITEM(expr, i);
            if (!PyList_CheckExact(part)) return 0;
            if (PyList_GET_SIZE(part) == 0) continue;
            int plain = add_conjunction(out, part, in);
            if (plain <= 0) return plain;
        }
        return 1;
    }
    PyObject *found = checked_literal(expr, in);
    if (found == Py_None || !found) return found ? 0 : -1;
    int failed = PyList_Append(out, found);
    Py_DECREF(found);
    return failed ? -1 : 1;
}

/* The arguments of literal() and conjunction(): (expr, predicates, variables, objects, ancestors, negation). */
static int parse_scope(PyObject *args, PyObject **expr, Scope *in) {
    if (!PyArg_ParseTuple(args, "OO!OO!O!p", expr, &PyDict_Type, &in->predicates, &in->variables, &PyDict_Type,
                          &in->objects, &PyDict_Type, &in->ancestors, &in->negation))
        return -1;
    if (in->variables == Py_None || PyDict_Check(in->variables)) return 0;
    PyErr_SetString(PyExc_TypeError, "variables must be a dict or None");
    return -1;
}

static PyObject *literal(PyObject *self, PyObject *args) {
    (void)self;
    PyObject *expr;
    Scope in;
    if (parse_scope(args, &expr, &in) < 0) return NULL;
    PyObject *found = checked_literal(expr, &in);
    return found == Py_None ? Py_NewRef(Py_None) : found;
}

static PyObject *conjunction(PyObject *self, PyObject *args) {
    (void)self;
    PyObject *expr;
    Scope in;
    if (parse_scope(args, &expr, &in) < 0) return NULL;
    PyObject *out = PyList_New(0);
    if (!out) return NULL;
    int plain = add_conjunction(out, expr, &in);
    if (plain == 1) return out;
    Py_DECREF(out);
    return plain == 0 ? Py_NewRef(Py_None) : NULL;
}

/* -- a plain action ------------------------------------------------------------------------------------------ */

static int is_text(PyObject *item, const char *text) {
    return PyUnicode_CheckExact(item) && PyUnicode_CompareWithASCIIString(item, text) == 0;
}

/* The last `pending` entries of `params`, variables so far, become (variable, kind) and go into `variables`; -1 on
   error. */
static int type_pending(PyObject *params, Py_ssize_t pending, PyObject *kind, PyObject *variables) {
    for (Py_ssize_t k = PyList_GET_SIZE(params) - pending; k < PyList_GET_SIZE(params); k++) {
        PyObject *var = PyList_GET_ITEM(params, k);
        PyObject *pair = PyTuple_Pack(2, var, kind);
        if (!pair || PyDict_SetItem(variables, var, kind) < 0) {
            Py_XDECREF(pair);
            return -1;
        }
        PyList_SET_ITEM(params, k, pair); /* the variable's reference moves into the pair's */
        Py_DECREF(var);
    }
    return 0;
}

/* `?a ?b - t ?c` into `params` (a list of (variable, type) tuples) and `variables` (variable -> type, the later of two
   alike winning, as Python's dict does): 1 when every name is a variable and every type a plain one the domain
   declares (in `types`), 0 when Python should look, -1 on error. */
static int add_parameters(PyObject *items, PyObject *types, PyObject *params, PyObject *variables) {
    Py_ssize_t n = PyList_GET_SIZE(items), pending = 0;
    for (Py_ssize_t i = 0; i < n; i++) {
        PyObject *item = PyList_GET_ITEM(items, i);
        if (!PyUnicode_CheckExact(item) || PyUnicode_GET_LENGTH(item) == 0) return 0;
        if (is_text(item, "-")) {
            if (i + 1 >= n || !pending) return 0;
            PyObject *kind = PyList_GET_ITEM(items, ++i);
            if (!PyUnicode_CheckExact(kind)) return 0; /* (either ...): Python's */
            int known = PyDict_Contains(types, kind);
            if (known <= 0) return known;
            if (type_pending(params, pending, kind, variables) < 0) return -1;
            pending = 0;
        } else {
            if (PyUnicode_READ_CHAR(item, 0) != '?' || PyList_Append(params, item) < 0) return PyErr_Occurred() ? -1 : 0;
            pending++;
        }
    }
    return type_pending(params, pending, root_type, variables) < 0 ? -1 : 1; /* untyped: object */
}

/* Whether an effect has an (increase ...) at its top, alone or in its (and ...): Python reads the action's cost. */
static int has_increase(PyObject *effect) {
    if (PyList_GET_SIZE(effect) == 0) return 0;
    if (is_text(PyList_GET_ITEM(effect, 0), "increase")) return 1;
    if (!is_text(PyList_GET_ITEM(effect, 0), "and")) return 0;
    for (Py_ssize_t i = 1; i < PyList_GET_SIZE(effect); i++) {
        PyObject *part = PyList_GET_ITEM(effect, i);
        if (PyList_CheckExact(part) && PyList_GET_SIZE(part) > 0 && is_text(PyList_GET_ITEM(part, 0), "increase"))
            return 1;
    }
    return 0;
}

/* action(section, predicates, constants, ancestors, types, negation): a STRIPS action's (name, parameters,
   precondition, add, delete) when plainly valid, else None (Python reads it: costs, ADL, errors). */
static PyObject *action(PyObject *self, PyObject *args) {
    (void)self;
    PyObject *section, *types;
    Scope in;
    if (!PyArg_ParseTuple(args, "O!O!O!O!O!p", &PyList_Type, &section, &PyDict_Type, &in.predicates, &PyDict_Type,
                          &in.objects, &PyDict_Type, &in.ancestors, &PyDict_Type, &types, &in.negation))
        return NULL;
    Py_ssize_t n = PyList_GET_SIZE(section);
    if (n < 2 || (n - 2) % 2 || !PyUnicode_CheckExact(PyList_GET_ITEM(section, 1))) Py_RETURN_NONE;
    static const char *const keys[3] = {":parameters", ":precondition", ":effect"};
    PyObject *fields[3] = {NULL, NULL, NULL};
    for (Py_ssize_t i = 2; i < n; i += 2) {
        PyObject *key = PyList_GET_ITEM(section, i), *value = PyList_GET_ITEM(section, i + 1);
        int which = -1;
        for (int k = 0; k < 3; k++)
            if (is_text(key, keys[k])) which = k;
        if (which < 0 || fields[which] || !PyList_CheckExact(value)) Py_RETURN_NONE;
        fields[which] = value;
    }
    if (fields[2] && has_increase(fields[2])) Py_RETURN_NONE;
    PyObject *params = PyList_New(0), *variables = PyDict_New(), *pre = PyList_New(0), *effects = PyList_New(0);
    PyObject *add = PyList_New(0), *delete = PyList_New(0), *result = NULL;
    int plain = params && variables && pre && effects && add && delete ? 1 : -1;
    if (plain == 1 && fields[0]) plain = add_parameters(fields[0], types, params, variables);
    in.variables = variables;
    if (plain == 1 && fields[1] && PyList_GET_SIZE(fields[1])) plain = add_conjunction(pre, fields[1], &in);
    in.negation = 1; /* an effect's (not ...) deletes */
    if (plain == 1 && fields[2] && PyList_GET_SIZE(fields[2])) plain = add_conjunction(effects, fields[2], &in);
    for (Py_ssize_t i = 0; plain == 1 && i < PyList_GET_SIZE(effects); i++) {
        PyObject *literal = PyList_GET_ITEM(effects, i);
        int positive = PyObject_IsTrue(PyTuple_GET_ITEM(literal, 1));
        if (positive < 0 || PyList_Append(positive ? add : delete, PyTuple_GET_ITEM(literal, 0)) < 0) plain = -1;
    }
    if (plain == 1) {
        PyObject *items[5] = {Py_NewRef(PyList_GET_ITEM(section, 1)), PyList_AsTuple(params), PyList_AsTuple(pre),
                              PyList_AsTuple(add), PyList_AsTuple(delete)};
        result = tuple_of(&PyTuple_Type, 5, items);
    } else if (plain == 0) {
        result = Py_NewRef(Py_None);
    }
    Py_XDECREF(params);
    Py_XDECREF(variables);
    Py_XDECREF(pre);
    Py_XDECREF(effects);
    Py_XDECREF(add);
    Py_XDECREF(delete);
    return result;
}

static PyMethodDef reader_methods[] = {
    {"sexpr", parse, METH_O,
     "sexpr(text) -> the single top-level s-expression as nested lists of lower-case str, or None where the text "
     "is not ASCII or not well formed (the Python reader then says where)."},
    {"bind", bind, METH_VARARGS,
     "bind(atom_type, condition_type, reserved, root_type): the reader's named tuples, the names that are no "
     "predicate's (and, not, =, ...) and the root type, once before atom() and literal()."},
    {"atom", atom, METH_VARARGS,
     "atom(expr, predicates, objects, ancestors) -> an Atom of a problem (no variables), or None where "
     "Python's checks should look."},
    {"literal", literal, METH_VARARGS,
     "literal(expr, predicates, variables, objects, ancestors, negation) -> a Condition, or None where Python's "
     "checks should look; a (not ...) only with `negation`."},
    {"action", action, METH_VARARGS,
     "action(section, predicates, constants, ancestors, types, negation) -> (name, parameters, precondition, add, "
     "delete) of a plainly valid STRIPS action (typed variables, conjunctions of literals, no cost), or None where "
     "Python's reader should look; a (not ...) in the precondition only with `negation`."},
    {"conjunction", conjunction, METH_VARARGS,
     "conjunction(expr, predicates, variables, objects, ancestors, negation) -> the list of Conditions of a literal "
     "or an (and ...) of them (nested, () parts skipped), or None where any part needs Python's checks."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef reader_module = {
    PyModuleDef_HEAD_INIT, "_reader", "The PDDL reader's fast pass in C.", -1, reader_methods, NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__reader(void) { return PyModule_Create(&reader_module); }
