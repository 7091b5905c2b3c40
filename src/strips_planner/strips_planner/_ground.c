/* Grounding's inner loop in C: every action's atoms under every one of its bindings, numbered, pruned to
 * what a relaxed exploration from the initial state reaches (delete effects and negative preconditions
 * ignored), and turned into the operators' bit masks.
 *
 * strips_planner.grounding does the PDDL-level work in Python (types, static preconditions, the
 * bindings) over predicate and object indices, and hands this module integer templates. An atom is a key
 * of `width` ints: its predicate's index, then its arguments' object indices, -1 past its arity.
 * Predicates and objects are numbered in sorted name order, so sorting the keys sorts the atoms as
 * (predicate, *arguments) name tuples, and the facts keep the order the pure-Python grounder gave them.
 */
#include "_atoms.h" /* Python.h, word, Rows, words_to_int; Atoms, sort_by_key, read_ints */

enum { PRE, PRE_NEG, ADD, DEL, KINDS };

/* -- the input ------------------------------------------------------------------------------------------ */

typedef struct {
    PyObject *name; /* borrowed from the arguments */
    int nparams, nbindings;
    int *values;          /* nbindings x nparams object indices */
    int count[KINDS + 1]; /* templates per kind, then their total */
    int *fixed, *param;   /* per template, `width` ints each: the key's fixed entries, and which entries come
                             from which parameter (-1: none) */
} Action;

typedef struct {
    int width, npredicates, nobjects;
} Shape;

/* An atom's key from (predicate, *objects); -1 with an exception set when malformed. */
static int read_key(PyObject *seq, const Shape *shape, int *key) {
    int n = read_ints(seq, key, shape->width, "an atom");
    if (n < 0) return -1;
    for (int i = n; i < shape->width; i++) key[i] = -1;
    int bad = n == 0 || key[0] < 0 || key[0] >= shape->npredicates;
    for (int i = 1; i < n; i++) bad |= key[i] < 0 || key[i] >= shape->nobjects;
    if (bad) PyErr_SetString(PyExc_ValueError, "an atom must be (predicate index, *object indices) in range");
    return bad ? -1 : 0;
}

/* A template (predicate, *arguments), an argument being a parameter's position (>= 0) or ~object for a
   constant (< 0), into its fixed entries and parameter sources. */
static int read_template(PyObject *seq, const Shape *shape, int nparams, int *fixed, int *param) {
    int n = read_ints(seq, fixed, shape->width, "a template");
    if (n < 0) return -1;
    int bad = n == 0 || fixed[0] < 0 || fixed[0] >= shape->npredicates;
    param[0] = -1;
    for (int i = 1; i < shape->width; i++) {
        param[i] = i < n && fixed[i] >= 0 ? fixed[i] : -1;
        if (i >= n) fixed[i] = -1;
        else if (fixed[i] >= 0) bad |= fixed[i] >= nparams;
        else bad |= (fixed[i] = ~fixed[i]) >= shape->nobjects;
    }
    if (bad) PyErr_SetString(PyExc_ValueError, "a template must be (predicate index, *argument codes) in range");
    return bad ? -1 : 0;
}

/* One action from (name, nparams, bindings, pre, pre_neg, add, delete). */
static int read_action(PyObject *item, const Shape *shape, Action *action) {
    PyObject *bindings, *kinds[KINDS];
    if (!PyArg_ParseTuple(item, "UiO!OOOO", &action->name, &action->nparams, &PyList_Type, &bindings, &kinds[PRE],
                          &kinds[PRE_NEG], &kinds[ADD], &kinds[DEL]))
        return -1;
    if (action->nparams < 0) {
        PyErr_SetString(PyExc_ValueError, "nparams must not be negative");
        return -1;
    }
    action->nbindings = (int)PyList_GET_SIZE(bindings);
    action->values = malloc(sizeof(int) * ((size_t)action->nbindings * (size_t)action->nparams + 1));
    PyObject *fast[KINDS] = {NULL};
    int total = 0, status = -1;
    for (int k = 0; k < KINDS; k++) {
        if (!(fast[k] = PySequence_Fast(kinds[k], "templates must be a sequence"))) goto done;
        total += action->count[k] = (int)PySequence_Fast_GET_SIZE(fast[k]);
    }
    action->count[KINDS] = total;
    size_t size = sizeof(int) * ((size_t)total * (size_t)shape->width + 1);
    action->fixed = malloc(size);
    action->param = malloc(size);
    if (!action->values || !action->fixed || !action->param) {
        PyErr_NoMemory();
        goto done;
    }
    for (int b = 0; b < action->nbindings; b++) {
        int *values = action->values + (size_t)b * (size_t)action->nparams;
        int n = read_ints(PyList_GET_ITEM(bindings, b), values, action->nparams, "a binding");
        if (n < 0) goto done;
        int bad = n != action->nparams;
        for (int p = 0; p < n; p++) bad |= values[p] < 0 || values[p] >= shape->nobjects;
        if (bad) {
            PyErr_Format(PyExc_ValueError, "a binding must hold %d object indices in range", action->nparams);
            goto done;
        }
    }
    for (int k = 0, t = 0; k < KINDS; k++)
        for (int i = 0; i < action->count[k]; i++, t++) {
            size_t at = (size_t)t * (size_t)shape->width;
            if (read_template(PySequence_Fast_GET_ITEM(fast[k], i), shape, action->nparams, action->fixed + at,
                              action->param + at))
                goto done;
        }
    status = 0;
done:
    for (int k = 0; k < KINDS; k++) Py_XDECREF(fast[k]);
    return status;
}

/* -- the output ----------------------------------------------------------------------------------------- */

/* The names (items of the tuple `names`) at indices `index[0 .. n)`, as a tuple. */
static PyObject *names_at(PyObject *names, const int *index, int n) {
    PyObject *tuple = PyTuple_New(n);
    for (int i = 0; tuple && i < n; i++) {
        PyObject *name = PyTuple_GET_ITEM(names, index[i]);
        Py_INCREF(name);
        PyTuple_SET_ITEM(tuple, i, name);
    }
    return tuple;
}

static void set_bit(word *mask, int bit) {
    if (bit >= 0) mask[bit >> 6] |= (word)1 << (bit & 63);
}

/* -- grounding ----------------------------------------------------------------------------------------- */

typedef struct {
    Shape shape;
    int nactions, nops;
    Action *actions;
    int *op_action, *op_binding;
    int *mention, *op_start; /* per operator, its templates' atoms (kinds in order) */
    Atoms atoms;
    int *init, ninit; /* the initial atoms */
    char *reached, *fired;
    int *bit_of;    /* per atom, its fact (bit), or -1 when unreachable */
    int *fact_atom; /* per fact, its atom */
    int nfacts, nwords;
} Grounding;

static void grounding_free(Grounding *g) {
    for (int i = 0; g->actions && i < g->nactions; i++) {
        free(g->actions[i].values);
        free(g->actions[i].fixed);
        free(g->actions[i].param);
    }
    free(g->actions);
    free(g->op_action);
    free(g->op_binding);
    free(g->mention);
    free(g->op_start);
    atoms_free(&g->atoms);
    free(g->init);
    free(g->reached);
    free(g->fired);
    free(g->bit_of);
    free(g->fact_atom);
}

/* Every operator's atoms, by key; the initial atoms first. */
static int instantiate(Grounding *g, PyObject *init, PyObject *actions) {
    const Shape *shape = &g->shape;
    int *key = malloc(sizeof(int) * (size_t)shape->width);
    g->nactions = (int)PyList_GET_SIZE(actions);
    g->actions = calloc((size_t)g->nactions + 1, sizeof(Action));
    g->ninit = (int)PyList_GET_SIZE(init);
    g->init = malloc(sizeof(int) * ((size_t)g->ninit + 1));
    int status = -1;
    if (!key || !g->actions || !g->init || atoms_init(&g->atoms, shape->width)) goto no_memory;
    for (int i = 0; i < g->ninit; i++) {
        if (read_key(PyList_GET_ITEM(init, i), shape, key)) goto done;
        if ((g->init[i] = atoms_add(&g->atoms, key)) < 0) goto no_memory;
    }
    size_t nmentions = 0;
    for (int a = 0; a < g->nactions; a++) {
        Action *action = &g->actions[a];
        if (read_action(PyList_GET_ITEM(actions, a), shape, action)) goto done;
        if (action->nbindings > INT_MAX / 2 - g->nops) {
            PyErr_SetString(PyExc_ValueError, "too many operators");
            goto done;
        }
        g->nops += action->nbindings;
        nmentions += (size_t)action->nbindings * (size_t)action->count[KINDS];
    }
    g->op_action = malloc(sizeof(int) * ((size_t)g->nops + 1));
    g->op_binding = malloc(sizeof(int) * ((size_t)g->nops + 1));
    g->op_start = malloc(sizeof(int) * ((size_t)g->nops + 1));
    g->mention = malloc(sizeof(int) * (nmentions + 1));
    if (!g->op_action || !g->op_binding || !g->op_start || !g->mention) goto no_memory;
    if (nmentions > INT_MAX) {
        PyErr_SetString(PyExc_ValueError, "too many atoms in the operators");
        goto done;
    }
    int o = 0, m = 0;
    for (int a = 0; a < g->nactions; a++) {
        const Action *action = &g->actions[a];
        for (int b = 0; b < action->nbindings; b++, o++) {
            const int *values = action->values + (size_t)b * (size_t)action->nparams;
            g->op_action[o] = a;
            g->op_binding[o] = b;
            g->op_start[o] = m;
            for (int t = 0; t < action->count[KINDS]; t++) {
                const int *fixed = action->fixed + (size_t)t * (size_t)shape->width;
                const int *param = action->param + (size_t)t * (size_t)shape->width;
                for (int i = 0; i < shape->width; i++) key[i] = param[i] < 0 ? fixed[i] : values[param[i]];
                if ((g->mention[m++] = atoms_add(&g->atoms, key)) < 0) goto no_memory;
            }
        }
    }
    g->op_start[o] = m;
    status = 0;
    goto done;
no_memory:
    PyErr_NoMemory();
done:
    free(key);
    return status;
}

/* Operator `o` fires: its add effects are reached, the new ones queued. */
static void fire(Grounding *g, int o, int *queue, int *tail) {
    const Action *action = &g->actions[g->op_action[o]];
    const int *add = g->mention + g->op_start[o] + action->count[PRE] + action->count[PRE_NEG];
    g->fired[o] = 1;
    for (int i = 0; i < action->count[ADD]; i++)
        if (!g->reached[add[i]]) g->reached[add[i]] = 1, queue[(*tail)++] = add[i];
}

/* The atoms and operators reachable from the initial atoms when only positive preconditions count: each
   operator waits for its missing preconditions, and each reached atom releases the operators that need it. */
static int explore(Grounding *g) {
    int natoms = g->atoms.natoms, npre = 0, status = -1, head = 0, tail = 0;
    size_t room = (size_t)g->op_start[g->nops] + 1;
    int *missing = malloc(sizeof(int) * ((size_t)g->nops + 1)), *queue = malloc(sizeof(int) * ((size_t)natoms + 1));
    int *row = malloc(sizeof(int) * room), *item = malloc(sizeof(int) * room);
    Rows consumers = {NULL, NULL};
    g->reached = calloc((size_t)natoms + 1, 1);
    g->fired = calloc((size_t)g->nops + 1, 1);
    if (!missing || !queue || !row || !item || !g->reached || !g->fired) goto done;
    for (int o = 0; o < g->nops; o++) {
        missing[o] = g->actions[g->op_action[o]].count[PRE];
        for (int k = 0; k < missing[o]; k++) row[npre] = g->mention[g->op_start[o] + k], item[npre++] = o;
    }
    if (rows_build(&consumers, natoms, row, item, npre)) goto done;
    for (int i = 0; i < g->ninit; i++)
        if (!g->reached[g->init[i]]) g->reached[g->init[i]] = 1, queue[tail++] = g->init[i];
    for (int o = 0; o < g->nops; o++)
        if (!missing[o]) fire(g, o, queue, &tail);
    while (head < tail) {
        int atom = queue[head++];
        for (int k = consumers.start[atom]; k < consumers.start[atom + 1]; k++)
            if (!--missing[consumers.items[k]]) fire(g, consumers.items[k], queue, &tail);
    }
    status = 0;
done:
    if (status) PyErr_NoMemory();
    free(missing);
    free(queue);
    free(row);
    free(item);
    rows_free(&consumers);
    return status;
}

/* The reached atoms become the facts, numbered in key order. */
static int number_facts(Grounding *g) {
    int natoms = g->atoms.natoms, range = g->shape.npredicates > g->shape.nobjects ? g->shape.npredicates : g->shape.nobjects;
    g->fact_atom = malloc(sizeof(int) * ((size_t)natoms + 1));
    g->bit_of = malloc(sizeof(int) * ((size_t)natoms + 1));
    if (!g->fact_atom || !g->bit_of) return -1;
    g->nfacts = 0;
    for (int a = 0; a < natoms; a++) {
        g->bit_of[a] = -1;
        if (g->reached[a]) g->fact_atom[g->nfacts++] = a;
    }
    if (sort_by_key(&g->atoms, g->fact_atom, g->nfacts, range)) return -1;
    for (int bit = 0; bit < g->nfacts; bit++) g->bit_of[g->fact_atom[bit]] = bit;
    g->nwords = g->nfacts ? (g->nfacts + 63) / 64 : 1;
    return 0;
}

/* The facts as `atom_type` (predicate, arguments), in bit order. */
static PyObject *facts_list(const Grounding *g, PyObject *predicates, PyObject *objects, PyTypeObject *atom_type) {
    PyObject *facts = PyList_New(g->nfacts);
    for (int bit = 0; facts && bit < g->nfacts; bit++) {
        const int *key = KEY(&g->atoms, g->fact_atom[bit]);
        int arity = 0;
        while (arity + 1 < g->shape.width && key[arity + 1] >= 0) arity++;
        PyObject *items[2] = {PyTuple_GET_ITEM(predicates, key[0]), names_at(objects, key + 1, arity)};
        Py_INCREF(items[0]);
        PyObject *fact = tuple_of(atom_type, 2, items);
        if (!fact) Py_CLEAR(facts);
        else PyList_SET_ITEM(facts, bit, fact);
    }
    return facts;
}

/* The fired operators, in order, as `operator_type` (name, arguments, pre, pre_neg, add, delete, effects) with
   int-bitset masks and no conditional effects (grounding.py adds them); delete leaves out what the operator adds. */
static PyObject *operators_list(const Grounding *g, PyObject *objects, PyTypeObject *operator_type) {
    size_t nw = (size_t)g->nwords;
    word *masks = malloc(sizeof(word) * KINDS * nw);
    PyObject *operators = masks ? PyList_New(0) : PyErr_NoMemory();
    for (int o = 0; operators && o < g->nops; o++) {
        if (!g->fired[o]) continue;
        const Action *action = &g->actions[g->op_action[o]];
        const int *atom = g->mention + g->op_start[o];
        memset(masks, 0, sizeof(word) * KINDS * nw);
        for (int k = 0; k < KINDS; k++)
            for (int i = 0; i < action->count[k]; i++) set_bit(masks + k * nw, g->bit_of[*atom++]);
        for (size_t w = 0; w < nw; w++) masks[DEL * nw + w] &= ~masks[ADD * nw + w];
        PyObject *items[3 + KINDS] = {action->name,
                                      names_at(objects, action->values + (size_t)g->op_binding[o] * (size_t)action->nparams,
                                               action->nparams)};
        Py_INCREF(action->name);
        for (int k = 0; k < KINDS; k++) items[2 + k] = words_to_int(masks + k * nw, g->nwords);
        items[2 + KINDS] = PyTuple_New(0);
        PyObject *op = tuple_of(operator_type, 3 + KINDS, items);
        if (!op || PyList_Append(operators, op)) Py_CLEAR(operators);
        Py_XDECREF(op);
    }
    free(masks);
    return operators;
}

/* The mask of `atoms` that are facts; their positions among `atoms` that are not go into `unreached`. */
static PyObject *atoms_mask(const Grounding *g, const int *atoms, int n, PyObject *unreached) {
    word *mask = calloc((size_t)g->nwords, sizeof(word));
    if (!mask) return PyErr_NoMemory();
    for (int i = 0; i < n; i++) {
        int bit = atoms[i] < 0 ? -1 : g->bit_of[atoms[i]];
        set_bit(mask, bit);
        if (bit < 0 && unreached) {
            PyObject *position = PyLong_FromLong(i);
            int failed = !position || PyList_Append(unreached, position);
            Py_XDECREF(position);
            if (failed) {
                free(mask);
                return NULL;
            }
        }
    }
    PyObject *result = words_to_int(mask, g->nwords);
    free(mask);
    return result;
}

/* The atoms of `keys` (-1 for one never met), into `atoms` (room for all of them). */
static int find_atoms(const Grounding *g, PyObject *keys, int *atoms) {
    int *key = malloc(sizeof(int) * (size_t)g->shape.width), status = 0;
    if (!key) return PyErr_NoMemory(), -1;
    for (Py_ssize_t i = 0; !status && i < PyList_GET_SIZE(keys); i++)
        if (!(status = read_key(PyList_GET_ITEM(keys, i), &g->shape, key))) atoms[i] = atoms_find(&g->atoms, key);
    free(key);
    return status;
}

static PyObject *ground(PyObject *Py_UNUSED(module), PyObject *args, PyObject *kwargs) {
    static char *keywords[] = {"predicates", "objects", "width", "init", "goal", "goal_neg", "actions",
                               "atom_type", "operator_type", NULL};
    PyObject *predicates, *objects, *init, *goal, *goal_neg, *actions, *result = NULL;
    PyTypeObject *atom_type = &PyTuple_Type, *operator_type = &PyTuple_Type;
    Grounding g;
    memset(&g, 0, sizeof g);
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O!O!iO!O!O!O!|O!O!", keywords, &PyTuple_Type, &predicates,
                                     &PyTuple_Type, &objects, &g.shape.width, &PyList_Type, &init, &PyList_Type, &goal,
                                     &PyList_Type, &goal_neg, &PyList_Type, &actions, &PyType_Type, &atom_type,
                                     &PyType_Type, &operator_type))
        return NULL;
    if (g.shape.width < 1) return PyErr_Format(PyExc_ValueError, "width must be at least 1");
    if (!PyType_IsSubtype(atom_type, &PyTuple_Type) || !PyType_IsSubtype(operator_type, &PyTuple_Type))
        return PyErr_Format(PyExc_TypeError, "atom_type and operator_type must be tuple types");
    g.shape.npredicates = (int)PyTuple_GET_SIZE(predicates);
    g.shape.nobjects = (int)PyTuple_GET_SIZE(objects);
    Py_ssize_t ngoal = PyList_GET_SIZE(goal), nneg = PyList_GET_SIZE(goal_neg);
    int *goal_atoms = malloc(sizeof(int) * ((size_t)(ngoal + nneg) + 1));
    if (!goal_atoms) return PyErr_NoMemory();
    if (instantiate(&g, init, actions) || explore(&g)) goto done;
    if (number_facts(&g)) {
        PyErr_NoMemory();
        goto done;
    }
    if (find_atoms(&g, goal, goal_atoms) || find_atoms(&g, goal_neg, goal_atoms + ngoal)) goto done;
    PyObject *unreached = PyList_New(0);
    PyObject *items[6] = {facts_list(&g, predicates, objects, atom_type), atoms_mask(&g, g.init, g.ninit, NULL),
                          atoms_mask(&g, goal_atoms, (int)ngoal, unreached),
                          atoms_mask(&g, goal_atoms + ngoal, (int)nneg, NULL), unreached, operators_list(&g, objects, operator_type)};
    result = tuple_of(&PyTuple_Type, 6, items);
done:
    free(goal_atoms);
    grounding_free(&g);
    return result;
}

/* -- an action's templates ------------------------------------------------------------------------------ */

/* `atom` (an Atom: predicate, args) as a template (number[predicate], *arguments), or with `head` given, (*head,
   *arguments) (an equality's filter): each argument its parameter's `position`, else ~its object's `index`. A new
   reference; NULL with the lookup's KeyError, as Python's dict raises it. */
static PyObject *template_of(PyObject *atom, PyObject *position, PyObject *index, PyObject *number, PyObject *head) {
    if (!PyTuple_Check(atom) || PyTuple_GET_SIZE(atom) != 2 || !PyTuple_Check(PyTuple_GET_ITEM(atom, 1)))
        return PyErr_Format(PyExc_TypeError, "templates() takes atoms as (predicate, args tuple)");
    PyObject *args = PyTuple_GET_ITEM(atom, 1);
    Py_ssize_t nhead = head ? PyTuple_GET_SIZE(head) : 1, nargs = PyTuple_GET_SIZE(args);
    PyObject *out = PyTuple_New(nhead + nargs);
    if (!out) return NULL;
    if (head) {
        for (Py_ssize_t i = 0; i < nhead; i++) PyTuple_SET_ITEM(out, i, Py_NewRef(PyTuple_GET_ITEM(head, i)));
    } else {
        PyObject *predicate = PyDict_GetItemWithError(number, PyTuple_GET_ITEM(atom, 0));
        if (!predicate) {
            if (!PyErr_Occurred()) PyErr_SetObject(PyExc_KeyError, PyTuple_GET_ITEM(atom, 0));
            Py_DECREF(out);
            return NULL;
        }
        PyTuple_SET_ITEM(out, 0, Py_NewRef(predicate));
    }
    for (Py_ssize_t i = 0; i < nargs; i++) {
        PyObject *arg = PyTuple_GET_ITEM(args, i), *code = PyDict_GetItemWithError(position, arg);
        if (code) {
            Py_INCREF(code);
        } else if (!PyErr_Occurred()) {
            PyObject *object = PyDict_GetItemWithError(index, arg);
            if (!object && !PyErr_Occurred()) PyErr_SetObject(PyExc_KeyError, arg);
            code = object ? PyNumber_Invert(object) : NULL;
        }
        if (!code) {
            Py_DECREF(out);
            return NULL;
        }
        PyTuple_SET_ITEM(out, nhead + i, code);
    }
    return out;
}

/* Appends each atom of `atoms` as a template to `out`; -1 on error. */
static int add_templates(PyObject *out, PyObject *atoms, PyObject *position, PyObject *index, PyObject *number) {
    for (Py_ssize_t i = 0; i < PyTuple_GET_SIZE(atoms); i++) {
        PyObject *made = template_of(PyTuple_GET_ITEM(atoms, i), position, index, number, NULL);
        if (!made || PyList_Append(out, made) < 0) {
            Py_XDECREF(made);
            return -1;
        }
        Py_DECREF(made);
    }
    return 0;
}

static PyObject *templates(PyObject *self, PyObject *args) {
    (void)self;
    PyObject *precondition, *add, *delete, *position, *index, *number;
    long nfluent;
    if (!PyArg_ParseTuple(args, "O!O!O!O!O!O!l", &PyTuple_Type, &precondition, &PyTuple_Type, &add, &PyTuple_Type,
                          &delete, &PyDict_Type, &position, &PyDict_Type, &index, &PyDict_Type, &number, &nfluent))
        return NULL;
    PyObject *joined = PyList_New(0), *filters = PyList_New(0), *pre = PyList_New(0), *pre_neg = PyList_New(0);
    PyObject *adds = PyList_New(0), *deletes = PyList_New(0);
    int failed = !joined || !filters || !pre || !pre_neg || !adds || !deletes;
    for (Py_ssize_t i = 0; !failed && i < PyTuple_GET_SIZE(precondition); i++) {
        PyObject *condition = PyTuple_GET_ITEM(precondition, i);
        if (!PyTuple_Check(condition) || PyTuple_GET_SIZE(condition) != 2) {
            PyErr_SetString(PyExc_TypeError, "templates() takes conditions as (atom, positive)");
            failed = 1;
            break;
        }
        PyObject *atom = PyTuple_GET_ITEM(condition, 0);
        if (!PyTuple_Check(atom) || PyTuple_GET_SIZE(atom) != 2) {
            PyErr_SetString(PyExc_TypeError, "templates() takes atoms as (predicate, args tuple)");
            failed = 1;
            break;
        }
        int positive = PyObject_IsTrue(PyTuple_GET_ITEM(condition, 1));
        if (positive < 0) {
            failed = 1;
            break;
        }
        PyObject *made;
        if (PyUnicode_CheckExact(PyTuple_GET_ITEM(atom, 0)) &&
            PyUnicode_CompareWithASCIIString(PyTuple_GET_ITEM(atom, 0), "=") == 0) { /* (positive, -1, *arguments) */
            PyObject *head = Py_BuildValue("(Oi)", positive ? Py_True : Py_False, -1);
            made = head ? template_of(atom, position, index, number, head) : NULL;
            Py_XDECREF(head);
            failed = !made || PyList_Append(filters, made) < 0;
            Py_XDECREF(made);
            continue;
        }
        if (!(made = template_of(atom, position, index, number, NULL))) {
            failed = 1;
            break;
        }
        int fluent = PyLong_AsLong(PyTuple_GET_ITEM(made, 0)) < nfluent;
        if (fluent && PyList_Append(positive ? pre : pre_neg, made) < 0) failed = 1;
        if (!failed && positive && PyList_Append(joined, made) < 0) failed = 1;
        if (!failed && !positive && !fluent) { /* a negative static precondition: (False, *template) */
            PyObject *head = PyTuple_Pack(1, Py_False), *filter = head ? PySequence_Concat(head, made) : NULL;
            failed = !filter || PyList_Append(filters, filter) < 0;
            Py_XDECREF(head);
            Py_XDECREF(filter);
        }
        Py_DECREF(made);
    }
    if (!failed) failed = add_templates(adds, add, position, index, number) < 0 ||
                          add_templates(deletes, delete, position, index, number) < 0;
    if (failed) {
        Py_XDECREF(joined);
        Py_XDECREF(filters);
        Py_XDECREF(pre);
        Py_XDECREF(pre_neg);
        Py_XDECREF(adds);
        Py_XDECREF(deletes);
        return NULL;
    }
    return Py_BuildValue("(NNNNNN)", joined, filters, pre, pre_neg, adds, deletes);
}

static PyMethodDef ground_methods[] = {
    {"templates", templates, METH_VARARGS,
     "templates(precondition, add, delete, position, index, number, nfluent) -> (joined, filters, pre, pre_neg, "
     "add, delete): an action's atoms as templates (number[predicate], *arguments), an argument its parameter's "
     "position or ~index[object]: the positive preconditions (joined), the checks (equalities (positive, -1, "
     "*arguments) and negative static preconditions (False, *template)), the fluent positive and negative "
     "preconditions (predicate number below nfluent), and the add and delete effects."},
    {"ground", (PyCFunction)(void (*)(void))ground, METH_VARARGS | METH_KEYWORDS,
     "ground(predicates, objects, width, init, goal, goal_neg, actions, atom_type=tuple, operator_type=tuple) -> "
     "(facts, init, goal, goal_neg, unreached_goals, operators).\n\n"
     "predicates, objects: tuples of names, sorted. An atom is (predicate index, *object indices), at most "
     "`width` ints. actions: (name, nparams, bindings, pre, pre_neg, add, delete), bindings a list of tuples of "
     "object indices, the others lists of templates (predicate index, *arguments), an argument being a "
     "parameter's position or ~object for a constant. Returns the reachable facts as (predicate, arguments) "
     "in sorted order (as atom_type), the masks of init, goal and goal_neg over them, the positions in `goal` of "
     "atoms that are not reachable, and the reachable operators as operator_type (name, arguments, pre, pre_neg, "
     "add, delete)."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef ground_module = {
    PyModuleDef_HEAD_INIT,
    .m_name = "_ground",
    .m_doc = "Grounding's inner loop: atoms numbered, relaxed reachability, operator masks.",
    .m_size = -1,
    .m_methods = ground_methods,
};

PyMODINIT_FUNC PyInit__ground(void) { return PyModule_Create(&ground_module); }
