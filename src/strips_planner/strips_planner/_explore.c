/* Relaxed exploration in C: the bindings of each action whose positive preconditions can ever hold together.
 *
 * Starting from the initial atoms (fluent and static), every newly reached atom seeds each precondition it
 * matches, and the action's other positive preconditions are joined against the atoms reached so far through
 * hash indices on the argument positions a join looks up (the semi-naive evaluation of Datalog-style
 * grounders). A binding is thus only ever built from atoms that hold in the relaxed task (delete effects and
 * negative fluent preconditions ignored), never by enumerating object combinations first. Types, equality and
 * negative static preconditions are checked as soon as their variables are bound; a parameter that no positive
 * precondition mentions ranges over the objects of its type.
 *
 * Atoms are numbered in the order they arrive, which is also the queue's order, and each index lists its atoms
 * in that order: a binding is found once, by the last of its atoms to arrive (preconditions listed before the
 * seed may use atoms up to the seed's arrival, those after it only earlier ones).
 *
 * strips_planner.grounding numbers predicates and objects and hands this module templates: (predicate,
 * *arguments), an argument being a parameter's position (>= 0) or ~object for a constant.
 */
#include "_atoms.h" /* Python.h; Atoms, sort_by_key, read_ints */

#define MAX_ARGS 32 /* parameters of an action, and arguments of a predicate */
#define SIGNAL_CHECK_MASK 0xFFFF /* check for Ctrl-C or a time limit's alarm every 65,536 join steps */

typedef struct {
    int *items;
    int n, room;
} Vec;

static int vec_push(Vec *v, int x) {
    if (v->n == v->room) {
        int room = v->room ? 2 * v->room : 4, *items = realloc(v->items, sizeof(int) * (size_t)room);
        if (!items) return -1;
        v->items = items;
        v->room = room;
    }
    v->items[v->n++] = x;
    return 0;
}

typedef struct {
    int pred, nargs, args[MAX_ARGS];
} Template;

typedef struct {
    int positive;
    Template atom; /* pred -1: the equality of its two arguments */
} Filter;

/* One step of a join: look a precondition's atoms up by its bound arguments, or (pred -1) range `param`, which
   no positive precondition mentions, over `choices`. */
typedef struct {
    int pred, index;
    int nkey, key[MAX_ARGS]; /* the bound arguments (parameters or ~constants) whose objects are the index's key */
    int nbinds, bind_pos[MAX_ARGS], bind_param[MAX_ARGS]; /* the parameters this step binds first */
    int nsame, same_p[MAX_ARGS], same_q[MAX_ARGS];        /* row positions that must agree */
    int earlier; /* 1: only atoms that arrived before the seed; 0: the seed itself too */
    Vec filters; /* the checks whose parameters are all bound after this step */
    int param;
    Vec choices;
} Step;

/* How an arriving atom seeds one precondition of one schema. */
typedef struct {
    int schema;
    Template seed;
    Vec filters; /* the checks the seed alone allows */
    int nsteps;
    Step *steps;
} Seeding;

typedef struct {
    int nparams, njoined, nfilters, nadds;
    unsigned char *allowed[MAX_ARGS]; /* per parameter, a flag per object; NULL: any object */
    Template *joined, *adds;          /* positive preconditions (fluent or static); add effects */
    Filter *filters;                  /* equalities and negative static preconditions */
    Atoms found;                      /* the bindings found, padded with -1 to at least one int */
} Schema;

typedef struct {
    int pred, npos, pos[MAX_ARGS];
} Index;

typedef struct {
    int width, nobjects, npredicates, nschemas, nseedings, nindices;
    Schema *schemas;
    Seeding *seedings;
    Index *indices;
    Vec *pred_indices, *pred_seedings; /* per predicate */
    Atoms atoms;                       /* the reached atoms, numbered as they arrive */
    Atoms bucket_keys;                 /* (index, *key) -> bucket */
    Vec *buckets;                      /* per bucket, its atoms in arrival order */
    int buckets_room;
    unsigned long steps; /* join steps taken, for the signal checks */
} Ctx;

static inline int value_of(int arg, const int *values) { return arg >= 0 ? values[arg] : ~arg; }

/* -- the reached atoms and their indices ----------------------------------------------------------------- */

static int index_insert(Ctx *c, int index, int atom) {
    const Index *ix = &c->indices[index];
    int key[MAX_ARGS + 1];
    const int *row = KEY(&c->atoms, atom) + 1;
    key[0] = index;
    for (int i = 0; i < ix->npos; i++) key[1 + i] = row[ix->pos[i]];
    for (int i = 1 + ix->npos; i < c->width; i++) key[i] = -1;
    int bucket = atoms_add(&c->bucket_keys, key);
    if (bucket < 0) return -1;
    if (bucket == c->buckets_room) {
        int room = 2 * c->buckets_room;
        Vec *buckets = realloc(c->buckets, sizeof(Vec) * (size_t)room);
        if (!buckets) return -1;
        memset(buckets + c->buckets_room, 0, sizeof(Vec) * (size_t)(room - c->buckets_room));
        c->buckets = buckets;
        c->buckets_room = room;
    }
    return vec_push(&c->buckets[bucket], atom);
}

/* The index of `pred`'s atoms by the arguments at `pos`, made (from the atoms reached so far) if new. */
static int index_of(Ctx *c, int pred, const int *pos, int npos) {
    for (int i = 0; i < c->nindices; i++) {
        const Index *ix = &c->indices[i];
        if (ix->pred == pred && ix->npos == npos && !memcmp(ix->pos, pos, sizeof(int) * (size_t)npos)) return i;
    }
    Index *indices = realloc(c->indices, sizeof(Index) * (size_t)(c->nindices + 1));
    if (!indices) return -1;
    c->indices = indices;
    int index = c->nindices++;
    indices[index].pred = pred;
    indices[index].npos = npos;
    memcpy(indices[index].pos, pos, sizeof(int) * (size_t)npos);
    if (vec_push(&c->pred_indices[pred], index)) return -1;
    for (int atom = 0; atom < c->atoms.natoms; atom++)
        if (KEY(&c->atoms, atom)[0] == pred && index_insert(c, index, atom)) return -1;
    return index;
}

/* `key` (pred, *objects, padded) reached: new atoms join the indices of their predicate. */
static int reach(Ctx *c, const int *key) {
    int before = c->atoms.natoms, atom = atoms_add(&c->atoms, key);
    if (atom < 0) return -1;
    if (atom < before) return 0;
    const Vec *indices = &c->pred_indices[key[0]];
    for (int i = 0; i < indices->n; i++)
        if (index_insert(c, indices->items[i], atom)) return -1;
    return 0;
}

/* -- joins ----------------------------------------------------------------------------------------------- */

static int filters_hold(const Ctx *c, const Schema *schema, const Vec *filters, const int *values) {
    int key[MAX_ARGS + 1];
    for (int i = 0; i < filters->n; i++) {
        const Filter *f = &schema->filters[filters->items[i]];
        int holds;
        if (f->atom.pred < 0) holds = value_of(f->atom.args[0], values) == value_of(f->atom.args[1], values);
        else {
            key[0] = f->atom.pred;
            for (int a = 0; a < f->atom.nargs; a++) key[1 + a] = value_of(f->atom.args[a], values);
            for (int a = 1 + f->atom.nargs; a < c->width; a++) key[a] = -1;
            holds = atoms_find(&c->atoms, key) >= 0; /* a static predicate's atoms are its initial ones */
        }
        if (holds != f->positive) return 0;
    }
    return 1;
}

static int found(Ctx *c, int s, const int *values) {
    Schema *schema = &c->schemas[s];
    int key[MAX_ARGS + 1] = {-1};
    memcpy(key, values, sizeof(int) * (size_t)schema->nparams);
    int before = schema->found.natoms, binding = atoms_add(&schema->found, key);
    if (binding < 0) return -1;
    if (binding < before) return 0;
    for (int i = 0; i < schema->nadds; i++) {
        const Template *add = &schema->adds[i];
        key[0] = add->pred;
        for (int a = 0; a < add->nargs; a++) key[1 + a] = value_of(add->args[a], values);
        for (int a = 1 + add->nargs; a < c->width; a++) key[a] = -1;
        if (reach(c, key)) return -1;
    }
    return 0;
}

static int join(Ctx *c, int s, int *values, const Step *steps, int nsteps, int k, int seed_arrival) {
    if (!(++c->steps & SIGNAL_CHECK_MASK) && PyErr_CheckSignals()) return -1; /* a join can take minutes */
    if (k == nsteps) return found(c, s, values);
    const Step *step = &steps[k];
    const Schema *schema = &c->schemas[s];
    if (step->pred < 0) {
        for (int i = 0; i < step->choices.n; i++) {
            values[step->param] = step->choices.items[i];
            if (filters_hold(c, schema, &step->filters, values) && join(c, s, values, steps, nsteps, k + 1, seed_arrival))
                return -1;
        }
        values[step->param] = -1;
        return 0;
    }
    int key[MAX_ARGS + 1];
    key[0] = step->index;
    for (int i = 0; i < step->nkey; i++) key[1 + i] = value_of(step->key[i], values);
    for (int i = 1 + step->nkey; i < c->width; i++) key[i] = -1;
    int bucket = atoms_find(&c->bucket_keys, key), last = seed_arrival - step->earlier;
    for (int i = 0; bucket >= 0 && i < c->buckets[bucket].n; i++) { /* the bucket grows as bindings are found */
        int atom = c->buckets[bucket].items[i];
        if (atom > last) break; /* listed in arrival order */
        const int *row = KEY(&c->atoms, atom) + 1;
        int ok = 1;
        for (int j = 0; ok && j < step->nsame; j++) ok = row[step->same_p[j]] == row[step->same_q[j]];
        for (int j = 0; ok && j < step->nbinds; j++) {
            int a = step->bind_param[j], obj = row[step->bind_pos[j]];
            ok = !schema->allowed[a] || schema->allowed[a][obj];
            values[a] = obj;
        }
        if (ok && filters_hold(c, schema, &step->filters, values) && join(c, s, values, steps, nsteps, k + 1, seed_arrival))
            return -1;
    }
    for (int j = 0; j < step->nbinds; j++) values[step->bind_param[j]] = -1;
    return 0;
}

/* -- planning a join ------------------------------------------------------------------------------------- */

/* Move the filters whose parameters are all bound now from `pending` into `out`. */
static int take(const Schema *schema, unsigned char *pending, const unsigned char *bound, Vec *out) {
    for (int f = 0; f < schema->nfilters; f++) {
        if (!pending[f]) continue;
        const Template *atom = &schema->filters[f].atom;
        int ready = 1;
        for (int a = 0; ready && a < atom->nargs; a++) ready = atom->args[a] < 0 || bound[atom->args[a]];
        if (ready) {
            pending[f] = 0;
            if (vec_push(out, f)) return -1;
        }
    }
    return 0;
}

/* The checks a seed of precondition `seed` (-1: none) allows at once, and the join after it: preconditions with
   the most bound arguments first (the fewest arguments on a tie, the first listed after that), then the
   parameters no precondition mentions. */
static int plan(Ctx *c, int s, int seed, Vec *now, Step **steps_out, int *nsteps) {
    const Schema *schema = &c->schemas[s];
    unsigned char bound[MAX_ARGS] = {0}, done[MAX_ARGS * 4 + 1] = {0};
    unsigned char *pending = malloc((size_t)schema->nfilters + 1);
    Step *steps = calloc((size_t)(schema->njoined + schema->nparams) + 1, sizeof(Step));
    *steps_out = steps;
    *nsteps = 0;
    int status = -1;
    if (!pending || !steps) goto out;
    memset(pending, 1, (size_t)schema->nfilters + 1);
    if (seed >= 0) {
        done[seed] = 1;
        for (int a = 0; a < schema->joined[seed].nargs; a++)
            if (schema->joined[seed].args[a] >= 0) bound[schema->joined[seed].args[a]] = 1;
    }
    if (take(schema, pending, bound, now)) goto out;
    for (int left = schema->njoined - (seed >= 0); left > 0; left--) {
        int best = -1, best_bound = -1, best_nargs = 0;
        for (int j = 0; j < schema->njoined; j++) {
            if (done[j]) continue;
            const Template *t = &schema->joined[j];
            int nbound = 0;
            for (int a = 0; a < t->nargs; a++) nbound += t->args[a] < 0 || bound[t->args[a]];
            if (nbound > best_bound || (nbound == best_bound && t->nargs < best_nargs))
                best = j, best_bound = nbound, best_nargs = t->nargs;
        }
        done[best] = 1;
        const Template *t = &schema->joined[best];
        Step *step = &steps[(*nsteps)++];
        int pos[MAX_ARGS], npos = 0, first[MAX_ARGS];
        for (int a = 0; a < schema->nparams; a++) first[a] = -1;
        step->pred = t->pred;
        step->earlier = best > seed;
        for (int p = 0; p < t->nargs; p++) {
            int a = t->args[p];
            if (a < 0 || bound[a]) {
                pos[npos++] = p;
                step->key[step->nkey++] = a;
            } else if (first[a] >= 0) {
                step->same_p[step->nsame] = p;
                step->same_q[step->nsame++] = first[a];
            } else {
                first[a] = p;
                step->bind_pos[step->nbinds] = p;
                step->bind_param[step->nbinds++] = a;
            }
        }
        for (int j = 0; j < step->nbinds; j++) bound[step->bind_param[j]] = 1;
        if ((step->index = index_of(c, t->pred, pos, npos)) < 0 || take(schema, pending, bound, &step->filters)) goto out;
    }
    for (int a = 0; a < schema->nparams; a++) {
        if (bound[a]) continue;
        bound[a] = 1;
        Step *step = &steps[(*nsteps)++];
        step->pred = -1;
        step->param = a;
        for (int obj = 0; obj < c->nobjects; obj++)
            if ((!schema->allowed[a] || schema->allowed[a][obj]) && vec_push(&step->choices, obj)) goto out;
        if (take(schema, pending, bound, &step->filters)) goto out;
    }
    status = 0;
out:
    free(pending);
    return status;
}

/* The binding an atom (its key's arguments) gives precondition `seed` of a schema, into `values`; 0 if none. */
static int seed_values(const Schema *schema, const Template *seed, const int *row, int *values) {
    for (int a = 0; a < schema->nparams; a++) values[a] = -1;
    for (int i = 0; i < seed->nargs; i++) {
        int arg = seed->args[i], obj = row[i];
        if (arg < 0) {
            if (~arg != obj) return 0;
        } else if (values[arg] < 0) {
            if (schema->allowed[arg] && !schema->allowed[arg][obj]) return 0;
            values[arg] = obj;
        } else if (values[arg] != obj) return 0;
    }
    return 1;
}

static int run(Ctx *c) {
    int values[MAX_ARGS], key[MAX_ARGS + 1];
    for (int s = 0; s < c->nschemas; s++) {
        const Schema *schema = &c->schemas[s];
        for (int j = 0; j < schema->njoined; j++) {
            Seeding *seeding = &c->seedings[c->nseedings++];
            seeding->schema = s;
            seeding->seed = schema->joined[j];
            if (plan(c, s, j, &seeding->filters, &seeding->steps, &seeding->nsteps) ||
                vec_push(&c->pred_seedings[seeding->seed.pred], c->nseedings - 1))
                return -1;
        }
    }
    for (int s = 0; s < c->nschemas; s++) { /* an action without positive preconditions: seeded by nothing */
        if (c->schemas[s].njoined) continue;
        Vec now = {NULL, 0, 0};
        Step *steps;
        int nsteps, failed = plan(c, s, -1, &now, &steps, &nsteps);
        for (int a = 0; a < MAX_ARGS; a++) values[a] = -1;
        failed = failed || (filters_hold(c, &c->schemas[s], &now, values) &&
                            join(c, s, values, steps, nsteps, 0, c->atoms.natoms));
        for (int k = 0; steps && k < nsteps; k++) free(steps[k].filters.items), free(steps[k].choices.items);
        free(steps);
        free(now.items);
        if (failed) return -1;
    }
    for (int atom = 0; atom < c->atoms.natoms; atom++) { /* the queue: atoms in arrival order */
        memcpy(key, KEY(&c->atoms, atom), sizeof(int) * (size_t)c->width); /* the table moves as it grows */
        const Vec *seedings = &c->pred_seedings[key[0]];
        for (int i = 0; i < seedings->n; i++) {
            const Seeding *seeding = &c->seedings[seedings->items[i]];
            const Schema *schema = &c->schemas[seeding->schema];
            if (seed_values(schema, &seeding->seed, key + 1, values) &&
                filters_hold(c, schema, &seeding->filters, values) &&
                join(c, seeding->schema, values, seeding->steps, seeding->nsteps, 0, atom))
                return -1;
        }
    }
    return 0;
}

/* -- input and output ------------------------------------------------------------------------------------ */

/* (pred, *arguments) into `t`: arguments are object indices (`nparams` -1) or parameter codes; `pred` may be -1
   where `equality` allows it. */
static int read_template(const Ctx *c, PyObject *seq, Template *t, int nparams, int equality, const char *what) {
    int ints[MAX_ARGS + 2], n = read_ints(seq, ints, MAX_ARGS + 1, what);
    if (n < 0) return -1;
    int bad = n < 1 || ints[0] >= c->npredicates || ints[0] < (equality ? -1 : 0) || (ints[0] >= 0 && n > c->width) ||
              (ints[0] < 0 && n != 3);
    t->pred = n ? ints[0] : 0;
    t->nargs = n - 1;
    for (int i = 1; !bad && i < n; i++) {
        int arg = ints[i];
        bad = nparams < 0 ? arg < 0 || arg >= c->nobjects : arg >= nparams || (arg < 0 && ~arg >= c->nobjects);
        t->args[i - 1] = arg;
    }
    if (bad) PyErr_Format(PyExc_ValueError, "%s must be (predicate index, *arguments) in range", what);
    return bad ? -1 : 0;
}

/* A list of templates into a new array. */
static Template *read_templates(const Ctx *c, PyObject *list, int *n, int nparams, const char *what) {
    PyObject *fast = PySequence_Fast(list, what);
    if (!fast) return NULL;
    *n = (int)PySequence_Fast_GET_SIZE(fast);
    Template *out = malloc(sizeof(Template) * ((size_t)*n + 1));
    if (!out) PyErr_NoMemory();
    for (int i = 0; out && i < *n; i++)
        if (read_template(c, PySequence_Fast_GET_ITEM(fast, i), &out[i], nparams, 0, what)) free(out), out = NULL;
    Py_DECREF(fast);
    return out;
}

/* One schema from (types, joined, filters, adds): types a tuple with, per parameter, None or the objects it
   may take; filters (positive, pred or -1 for equality, *arguments). */
static int read_schema(const Ctx *c, PyObject *item, Schema *schema) {
    PyObject *types, *joined, *filters, *adds, *fast = NULL;
    if (!PyArg_ParseTuple(item, "O!OOO", &PyTuple_Type, &types, &joined, &filters, &adds)) return -1;
    schema->nparams = (int)PyTuple_GET_SIZE(types);
    if (schema->nparams > MAX_ARGS) {
        PyErr_Format(PyExc_ValueError, "an action with %d parameters: at most %d", schema->nparams, MAX_ARGS);
        return -1;
    }
    if (atoms_init(&schema->found, schema->nparams ? schema->nparams : 1)) return PyErr_NoMemory(), -1;
    for (int a = 0; a < schema->nparams; a++) {
        PyObject *members = PyTuple_GET_ITEM(types, a);
        if (members == Py_None) continue;
        int *objects = malloc(sizeof(int) * ((size_t)c->nobjects + 1)), n;
        schema->allowed[a] = calloc((size_t)c->nobjects + 1, 1);
        if (!objects || !schema->allowed[a]) return free(objects), PyErr_NoMemory(), -1;
        n = read_ints(members, objects, c->nobjects, "a parameter's objects");
        for (int i = 0; i < n; i++) {
            if (objects[i] < 0 || objects[i] >= c->nobjects) n = -1, PyErr_SetString(PyExc_ValueError, "an object out of range");
            else schema->allowed[a][objects[i]] = 1;
        }
        free(objects);
        if (n < 0) return -1;
    }
    if (!(schema->joined = read_templates(c, joined, &schema->njoined, schema->nparams, "a precondition")) ||
        !(schema->adds = read_templates(c, adds, &schema->nadds, schema->nparams, "an add effect")) ||
        !(fast = PySequence_Fast(filters, "filters must be a sequence")))
        return -1;
    if (schema->njoined > MAX_ARGS * 4) {
        Py_DECREF(fast);
        PyErr_Format(PyExc_ValueError, "an action with %d positive preconditions: at most %d", schema->njoined, MAX_ARGS * 4);
        return -1;
    }
    schema->nfilters = (int)PySequence_Fast_GET_SIZE(fast);
    schema->filters = malloc(sizeof(Filter) * ((size_t)schema->nfilters + 1));
    int status = schema->filters ? 0 : (PyErr_NoMemory(), -1);
    for (int f = 0; !status && f < schema->nfilters; f++) {
        PyObject *entry = PySequence_Fast_GET_ITEM(fast, f), *rest = NULL;
        Filter *filter = &schema->filters[f];
        if (!PyTuple_Check(entry) || PyTuple_GET_SIZE(entry) < 2) {
            PyErr_SetString(PyExc_ValueError, "a filter must be (positive, predicate index or -1, *arguments)");
            status = -1;
        } else if ((filter->positive = PyObject_IsTrue(PyTuple_GET_ITEM(entry, 0))) < 0 ||
                   !(rest = PyTuple_GetSlice(entry, 1, PyTuple_GET_SIZE(entry))) ||
                   read_template(c, rest, &filter->atom, schema->nparams, 1, "a filter"))
            status = -1;
        Py_XDECREF(rest);
    }
    Py_DECREF(fast);
    return status;
}

/* Each schema's bindings as a sorted list of tuples. */
static PyObject *bindings_lists(const Ctx *c) {
    PyObject *result = PyList_New(c->nschemas);
    for (int s = 0; result && s < c->nschemas; s++) {
        const Schema *schema = &c->schemas[s];
        int n = schema->found.natoms, *order = malloc(sizeof(int) * ((size_t)n + 1));
        PyObject *list = order ? PyList_New(n) : PyErr_NoMemory();
        for (int i = 0; list && i < n; i++) order[i] = i;
        if (list && sort_by_key(&schema->found, order, n, c->nobjects)) {
            Py_CLEAR(list);
            PyErr_NoMemory();
        }
        for (int i = 0; list && i < n; i++) {
            PyObject *binding = PyTuple_New(schema->nparams);
            for (int a = 0; binding && a < schema->nparams; a++) {
                PyObject *obj = PyLong_FromLong(KEY(&schema->found, order[i])[a]);
                if (!obj) Py_CLEAR(binding);
                else PyTuple_SET_ITEM(binding, a, obj);
            }
            if (!binding) Py_CLEAR(list);
            else PyList_SET_ITEM(list, i, binding);
        }
        free(order);
        if (!list) Py_CLEAR(result);
        else PyList_SET_ITEM(result, s, list);
    }
    return result;
}

static void ctx_free(Ctx *c) {
    for (int s = 0; c->schemas && s < c->nschemas; s++) {
        Schema *schema = &c->schemas[s];
        for (int a = 0; a < MAX_ARGS; a++) free(schema->allowed[a]);
        free(schema->joined);
        free(schema->adds);
        free(schema->filters);
        if (schema->found.keys || schema->found.slots) atoms_free(&schema->found);
    }
    for (int i = 0; c->seedings && i < c->nseedings; i++) {
        Seeding *seeding = &c->seedings[i];
        for (int k = 0; seeding->steps && k < seeding->nsteps; k++)
            free(seeding->steps[k].filters.items), free(seeding->steps[k].choices.items);
        free(seeding->steps);
        free(seeding->filters.items);
    }
    for (int p = 0; p < c->npredicates; p++) {
        if (c->pred_indices) free(c->pred_indices[p].items);
        if (c->pred_seedings) free(c->pred_seedings[p].items);
    }
    for (int b = 0; c->buckets && b < c->bucket_keys.natoms; b++) free(c->buckets[b].items);
    free(c->schemas);
    free(c->seedings);
    free(c->indices);
    free(c->pred_indices);
    free(c->pred_seedings);
    free(c->buckets);
    if (c->atoms.keys || c->atoms.slots) atoms_free(&c->atoms);
    if (c->bucket_keys.keys || c->bucket_keys.slots) atoms_free(&c->bucket_keys);
}

static PyObject *explore(PyObject *Py_UNUSED(module), PyObject *args) {
    PyObject *init, *schemas, *result = NULL;
    Ctx c;
    memset(&c, 0, sizeof c);
    if (!PyArg_ParseTuple(args, "iiiO!O!", &c.npredicates, &c.nobjects, &c.width, &PyList_Type, &init, &PyList_Type,
                          &schemas))
        return NULL;
    if (c.width < 1 || c.width > MAX_ARGS + 1 || c.npredicates < 0 || c.nobjects < 0)
        return PyErr_Format(PyExc_ValueError, "width must be 1 to %d (predicates of at most %d arguments), counts >= 0",
                            MAX_ARGS + 1, MAX_ARGS);
    c.nschemas = (int)PyList_GET_SIZE(schemas);
    c.schemas = calloc((size_t)c.nschemas + 1, sizeof(Schema));
    c.pred_indices = calloc((size_t)c.npredicates + 1, sizeof(Vec));
    c.pred_seedings = calloc((size_t)c.npredicates + 1, sizeof(Vec));
    c.buckets_room = 64;
    c.buckets = calloc((size_t)c.buckets_room, sizeof(Vec));
    if (!c.schemas || !c.pred_indices || !c.pred_seedings || !c.buckets || atoms_init(&c.atoms, c.width) ||
        atoms_init(&c.bucket_keys, c.width)) {
        PyErr_NoMemory();
        goto done;
    }
    int nseedings = 0;
    for (int s = 0; s < c.nschemas; s++) {
        if (read_schema(&c, PyList_GET_ITEM(schemas, s), &c.schemas[s])) goto done;
        nseedings += c.schemas[s].njoined;
    }
    if (!(c.seedings = calloc((size_t)nseedings + 1, sizeof(Seeding)))) {
        PyErr_NoMemory();
        goto done;
    }
    int key[MAX_ARGS + 1];
    for (Py_ssize_t i = 0; i < PyList_GET_SIZE(init); i++) {
        Template atom;
        if (read_template(&c, PyList_GET_ITEM(init, i), &atom, -1, 0, "an initial atom")) goto done;
        key[0] = atom.pred;
        for (int a = 0; a < c.width - 1; a++) key[1 + a] = a < atom.nargs ? atom.args[a] : -1;
        if (reach(&c, key)) {
            PyErr_NoMemory();
            goto done;
        }
    }
    if (run(&c)) {
        if (!PyErr_Occurred()) PyErr_NoMemory();
        goto done;
    }
    result = bindings_lists(&c);
done:
    ctx_free(&c);
    return result;
}

static PyMethodDef explore_methods[] = {
    {"explore", explore, METH_VARARGS,
     "explore(npredicates, nobjects, width, init, schemas) -> a sorted list of bindings per schema.\n\n"
     "init: atoms (predicate index, *object indices), at most `width` ints. schemas: (types, joined, filters, "
     "adds) per action: types a tuple with, per parameter, None (any object) or the object indices it may take; "
     "joined and adds lists of templates (predicate index, *arguments), an argument being a parameter's position "
     "or ~object for a constant; filters (positive, predicate index or -1 for equality, *arguments), checked "
     "against the initial atoms. A binding is a tuple of object indices, one per parameter."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef explore_module = {
    PyModuleDef_HEAD_INIT,
    .m_name = "_explore",
    .m_doc = "Grounding's relaxed exploration: every action's bindings whose positive preconditions can hold together.",
    .m_size = -1,
    .m_methods = explore_methods,
};

PyMODINIT_FUNC PyInit__explore(void) { return PyModule_Create(&explore_module); }
