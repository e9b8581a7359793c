"""Cheaper numba internals while numba compiles navkit's kernels (private).

Pieces of numba's own work that cost a first use time and change nothing in
what numba makes of it (issue 17; measured on a cold ``astar`` and a cold
``FieldDStar`` plan, numba 0.68):

* **Error-message markup.** numba's compiler uses exceptions for flow control
  (a value that has no numba type, a float that cannot be a literal, an
  overload template that does not match): about 5,000 a first ``astar`` and
  8,700 a first Field D* plan. Each message is marked up with numba's colour
  scheme (``numba.core.errors.HighlightColorScheme._markup``), which calls
  colorama's ``init()`` and ``deinit()`` every time; they wrap and swap
  ``sys.stdout`` and ``sys.stderr`` and back (about 20 µs a message: 0.1 s of
  a first ``astar``, 0.17 s of a Field D* plan). While a navkit kernel compiles,
  the scheme gets a ``_markup`` that builds the same string (the same bytes,
  colour codes included) without touching the streams.
* **Compile-flag comparisons.** numba's ``@overload`` templates cache what
  they compiled by (context, argument types, flags), and every operator an
  ``@overload`` template might implement (``a[i]``, ``a + b``, ...) looks that
  cache up, often for several templates. ``TargetConfig.__hash__`` and
  ``__eq__`` build a dict of every option (22 property reads) each time:
  about 5,000 hashes and 10,000 comparisons, 0.4-0.5 s, of a first ``astar``,
  11,000 and 17,000, 0.6 s, of a Field D* plan. While a navkit kernel
  compiles, ``__hash__`` returns the value numba's own computes, remembered
  per class (it depends on the option names alone: numba hashes the sorted
  names of the options dict),
  and ``__eq__`` compares the options set (``_values``), each filled in with
  the class's defaults where unset: the dicts numba's own ``values()`` builds,
  without the property reads. Flags of another class, or of a class that
  reads its options otherwise, go to numba's own comparison.
* **Typing the same call again** (review 22). numba types each operator
  and builtin call (``a + b``, ``a[i]``, ``bool(x)``) by trying the
  function's templates in turn, at every call site and again at every pass
  of type inference over a kernel: 3,579 times, for 120 distinct argument
  type sets, in a first Field D* plan. A call answered through a plain
  template (not an ``@overload`` or ``@intrinsic``, which compile code for
  the compile's flags) is answered from a memo the next time: the same
  signature object, and numba's record of the template is written again
  (:func:`_call_type_method`).
* **LLVM type sizes** (review 22). llvmlite sizes a type by printing and
  parsing a module declaring it (0.25 ms), 531 times in a first Field D*
  plan, for 83 distinct types: sizes come from a memo
  (:func:`_abi_size_method`).
* **Whether an implementation takes ``loc``** (review 22): numba builds the
  ``inspect.signature`` of a lowering implementation each time it fetches
  it (1,442 times a Field D* plan); answered from a memo per function
  object (:func:`_has_loc_function`).
* **Variable lists** (review 22): numba lists an IR statement's variables by
  one recursive call per attribute value (630,000 calls a Field D* plan);
  the items of a container are tested in place (:func:`_list_vars_method`).
* **Live variables** (review 38): numba finds the variables live at each
  block's entry (``analysis.compute_live_map``, after every pass that
  changes the IR: 1,955 times in ``navkit warmup``) by fix-point sweeps
  over sets holding nearly every variable of the function; the same sweeps
  run on ints with a bit per variable and give the same sets
  (:func:`_live_map_function`): 1.75 -> 0.41 s of ``navkit warmup``.
* **Use-defs and dead variables** (review 39): the variables each block
  uses and defines (``analysis.compute_use_defs``, 2,147 times in ``navkit
  warmup``) are listed once per statement, without a call per value
  (:func:`_use_defs_function`: 0.89 -> 0.38 s), and numba's check that
  every live variable dies somewhere (``analysis.compute_dead_maps``, 1,964
  times) unions the blocks' sets in place (:func:`_dead_maps_function`:
  0.42 -> 0.27 s); both give numba's sets, built in the same order, at every
  call of ``navkit warmup`` (compared in one run each, numba 0.62 and 0.68).
  Installed also where numba's modules imported them by name.

The four of review 22 took a cold first Field D* plan (plan, cost update,
replan) from 3.08 to 2.63 s CPU (medians of 7 alternating runs on a 2-core
machine), ``astar`` 1.94 -> 1.61 s, jump point search 2.33 -> 1.91 s,
``MapPlanner.plan`` 1.77 -> 1.49 s (medians of 5) and ``navkit warmup``
25.6 -> 19.5 s (medians of 3). numba makes the same LLVM IR with and without
them: all 149 kernel signatures ``navkit warmup`` compiles, compared on numba
0.62 and 0.68.

All are switched on when the compile of a navkit kernel starts and back off
when the compiling thread releases numba's compiler lock, through the
listeners :mod:`navkit._shared.compile_gc` registers; compiles of other code
(the user's own kernels) run with numba as it is, except a user's kernel that
calls a navkit one, whose compile keeps the shortcuts from the navkit
kernel's compile to its own end: the shortcuts give the same answers and the
same messages, so nothing it compiles or reports changes (the memos keep
only what numba answered; their entries stay true, as a function type
gaining templates is another type). A ``TargetConfig``
class whose ``values`` or option properties are not the ones numba makes is
always left to numba's own methods.

The switch is one for the whole process while compiles are per thread, so,
as with the collector's pauses, the compiles under way are counted
process-wide: the first to start switches the shortcuts on, the last to end
puts numba's own methods back (and only its own: a method someone else
installed meanwhile is left in place). A child forked meanwhile keeps the
forking thread's count alone and, with none, gets numba's methods back.

:data:`ENABLED` turns the whole thing off (``navkit._shared.compile_shortcuts.ENABLED
= False``: compiles run with numba as it is; for measurements and tests).
"""

from __future__ import annotations

import importlib
import os
import sys
import threading
from collections import defaultdict
from collections.abc import Callable
from typing import Any

__all__ = ["ENABLED", "active", "begin", "end"]

#: Whether navkit compiles switch the shortcuts on (read when a compile starts).
ENABLED = True

#: Guards the three below (re-entrant, as compile_gc's).
_LOCK = threading.RLock()
#: Compiles with the shortcuts under way in every thread.
_COUNT = 0
#: What was replaced while the shortcuts are on: (owner, name, ours, replaced or
#: _MISSING for an attribute the owner did not have itself).
_SAVED: list[tuple[Any, str, Any, Any]] = []
#: This thread's share of the count (``count``): all that survives a fork.
_THREAD = threading.local()

_MISSING = object()

#: Per class: whether its values() and option properties are numba's own.
_PLAIN: dict[type, bool] = {}
#: Per class: its options' defaults.
_DEFAULTS: dict[type, dict[str, Any]] = {}


def _plain(cls: type, target_config: Any) -> bool:
    """Whether ``cls`` reads its options as numba's ``TargetConfig`` makes them.

    That is: ``values`` is ``TargetConfig.values``, and every option is a
    property made by numba's metaclass (``self._values.get(name, default)``).
    Only then do equal ``_values`` mean equal ``values()``.
    """
    plain = _PLAIN.get(cls)
    if plain is None:
        plain = getattr(cls, "values", None) is target_config.values
        for name in getattr(cls, "options", {}):
            prop = getattr(cls, name, None)
            getter = getattr(prop, "fget", None)
            qualname = getattr(getter, "__qualname__", "")
            if not isinstance(prop, property) or not qualname.endswith("make_prop.<locals>.getter"):
                plain = False
        _PLAIN[cls] = plain
    return plain


def _defaults(cls: Any) -> dict[str, Any]:
    """Every option of a ``TargetConfig`` class and its default."""
    defaults: dict[str, Any] | None = _DEFAULTS.get(cls)
    if defaults is None:
        defaults = _DEFAULTS[cls] = {name: opt.default for name, opt in cls.options.items()}
    return defaults


def _flag_methods(target_config: Any) -> tuple[Callable[..., Any], Callable[..., Any]]:
    """``__hash__`` and ``__eq__`` for numba's ``TargetConfig``, quicker and the same."""
    numba_hash = target_config.__hash__
    numba_eq = target_config.__eq__
    hashes: dict[type, int] = {}  # numba's hash per class: it depends on the option names

    def __hash__(self: Any) -> int:
        cls = type(self)
        value = hashes.get(cls)
        if value is None:
            value = numba_hash(self)
            if _plain(cls, target_config):
                hashes[cls] = value
        return value

    def __eq__(self: Any, other: Any) -> Any:
        cls = type(self)
        if type(other) is not cls or not _plain(cls, target_config):
            return numba_eq(self, other)
        mine, theirs = self._values, other._values
        if mine == theirs:
            return True
        # numba's values(): every option, set or default (the getters numba makes).
        defaults = _defaults(cls)
        full_mine, full_theirs = {**defaults, **mine}, {**defaults, **theirs}
        if len(full_mine) != len(defaults) or len(full_theirs) != len(defaults):
            return numba_eq(self, other)  # something else in _values: numba's way
        return full_mine == full_theirs

    return __hash__, __eq__


def _markup_method(errors: Any) -> Callable[..., str]:
    """numba's ``HighlightColorScheme._markup`` without colorama's stream swaps.

    The same string: the colour and style codes, the message, colorama's
    reset code, through the same UTF-8 round trip (a message that cannot be
    encoded raises as numba's does).
    """
    style_codes = errors.Style

    def _markup(msg: str, color: str | None = None, style: str | None = style_codes.BRIGHT) -> str:
        features = ""
        if color:
            features += color
        if style:
            features += style
        buffer = bytearray(b"")
        buffer += features.encode("utf-8")
        buffer += msg.encode("utf-8")
        buffer += style_codes.RESET_ALL.encode("utf-8")
        return buffer.decode("utf-8")

    return _markup


#: Typings of calls that numba resolved through a plain template (see
#: :func:`_call_type_method`): (function type, typing context, target, argument
#: types, keyword types) -> (signature, implementation key). Kept for the
#: process: the entries stay true (a function type gaining templates is
#: another type, and so another key).
_CALL_TYPES: dict[tuple[Any, ...], tuple[Any, Any]] = {}
#: ABI sizes of LLVM types numba asked for (see :func:`_abi_size_method`):
#: (id of the target context, the type's text) -> (the context, size in bytes).
_ABI_SIZES: dict[tuple[int, str], tuple[Any, int]] = {}


def _call_type_method(
    function_class: Any, numba_method: Callable[..., Any], get_local_target: Callable[..., Any]
) -> Callable[..., Any]:
    """``Function.get_call_type`` answering repeated calls from a memo, the same as numba's.

    numba types every operator and builtin call (``a + b``, ``a[i]``,
    ``bool(x)``) by trying, at each call site and at each pass of type
    inference over a kernel, every template registered for the function
    (about twenty for ``+``, NumPy's ufunc rules among them) until one
    accepts the argument types. A first Field D* plan types 3,579 such calls
    with 120 distinct argument type sets. When numba's own method answered
    through a plain template (its implementation key is the function itself:
    not an ``@overload`` or ``@intrinsic``, which compile code of their own
    for the compile's flags), the answer depends on the argument types alone:
    the same call later gets the same signature object, and numba's record of
    the template that answered (``_impl_keys``, read when the call is
    lowered) is written again as numba writes it. Anything else (another
    class of function type, an unhashable argument type, a failure) goes to
    numba's method.
    """
    memo = _CALL_TYPES

    def get_call_type(self: Any, context: Any, args: Any, kws: Any) -> Any:
        if type(self) is not function_class:
            return numba_method(self, context, args, kws)
        try:
            key = (self, context, get_local_target(context), tuple(args), tuple(kws.items()))
            hit = memo.get(key)
        except TypeError:  # an unhashable argument type: numba's way
            return numba_method(self, context, args, kws)
        if hit is not None:
            sig, impl = hit
            self._impl_keys[sig.args] = impl
            return sig
        sig = numba_method(self, context, args, kws)
        if sig is not None:
            impl = self._impl_keys.get(sig.args)
            if impl is self.typing_key:
                memo[key] = (sig, impl)
        return sig

    return get_call_type


def _abi_size_method(numba_method: Callable[..., int]) -> Callable[..., int]:
    """``BaseContext.get_abi_sizeof`` answering each LLVM type's size from a memo.

    llvmlite finds a type's size by writing a module declaring a global of
    that type as text and having LLVM parse it (about 0.25 ms): numba asks
    for every stack slot it lowers (531 times in a first Field D* plan, for
    83 distinct types: about 0.05 s). llvmlite types are equal when their text
    is; a type naming an identified structure (``%"name"``, whose body is
    elsewhere) is left to numba.
    """
    memo = _ABI_SIZES

    def get_abi_sizeof(self: Any, ty: Any) -> int:
        text = str(ty)
        if "%" in text:
            return numba_method(self, ty)
        entry = memo.get((id(self), text))
        if entry is not None and entry[0] is self:
            return entry[1]
        size = numba_method(self, ty)
        memo[(id(self), text)] = (self, size)
        return size

    return get_abi_sizeof


#: Whether lowering implementations take ``loc`` (see :func:`_has_loc_function`):
#: id -> (the implementation, the answer); the implementation is kept, so its
#: id is not reused.
_HAS_LOC: dict[int, tuple[Any, bool]] = {}


def _has_loc_function(numba_has_loc: Callable[[Any], bool]) -> Callable[[Any], bool]:
    """numba's ``_has_loc`` answering from a memo per implementation.

    Every time numba's lowering fetches the implementation of an operation
    (``a + b``, ``a[i]``: 1,442 times in a first Field D* plan, for a few
    dozen implementations) it asks whether the implementation takes a
    ``loc`` argument, by building its ``inspect.signature`` (about 35 µs).
    The answer of one function object does not change.
    """
    memo = _HAS_LOC

    def _has_loc(fn: Any) -> bool:
        entry = memo.get(id(fn))
        if entry is not None and entry[0] is fn:
            return entry[1]
        answer = numba_has_loc(fn)
        memo[id(fn)] = (fn, answer)
        return answer

    return _has_loc


def _list_vars_method(var_class: Any, inst_class: Any) -> Callable[..., list[Any]]:
    """``Inst._rec_list_vars`` without a call per leaf value: the same list, in order.

    numba lists the variables of an IR statement by recursing into every
    attribute of the statement (and of the expressions in it), one call per
    value, a source location or an operator included: 630,000 calls in a
    first Field D* plan, from the analyses its passes repeat (use-defs,
    liveness, variable deletion). This one tests the items of a container
    in place and recurses only into nested containers, through the method in
    place (as numba does), so an override in a subclass is still used.
    """
    containers = (list, tuple, dict)

    def _rec_list_vars(self: Any, val: Any) -> list[Any]:
        if isinstance(val, var_class):
            return [val]
        if isinstance(val, inst_class):
            result: list[Any] = val.list_vars()
            return result
        if isinstance(val, (list, tuple)):
            items: Any = val
        elif isinstance(val, dict):
            items = val.values()
        else:
            return []
        out: list[Any] = []
        for item in items:
            if isinstance(item, var_class):
                out.append(item)
            elif isinstance(item, inst_class):
                out.extend(item.list_vars())
            elif isinstance(item, containers):
                out.extend(self._rec_list_vars(item))
        return out

    return _rec_list_vars


def _live_map_function(numba_live_map: Callable[..., Any]) -> Callable[..., dict[Any, set[str]]]:
    """``analysis.compute_live_map`` with each block's variable sets as bits of an int.

    numba finds the variables live at each block's entry (for its variable
    deletions and dead-code removal, after every pass that changes the IR) by
    two fix-point sweeps over the blocks: the variables defined or used in
    any block reaching a block, then those used later without being defined
    again. The first sets hold nearly every variable of the function, and
    their set unions took about 6 % of a cold ``Simulation.run``'s compile
    (0.72 s of 12 in ``navkit warmup``'s simulation step, 1.75 s of the whole
    warm-up). The same sweeps, in the same order, are made here on ints with
    a bit per variable (an OR of a few machine words each), and the live sets
    built from the bits: the same sets for every block (equal to numba's at
    each of the 1,955 calls of ``navkit warmup``, compared in one run), 0.13 s
    and 0.41 s. Installed only where numba's own sweeps follow the graph's
    topological order, as numba 0.68's do (elsewhere numba's own is kept).
    """

    def compute_live_map(cfg: Any, blocks: Any, var_use_map: Any, var_def_map: Any) -> Any:
        topo_order = cfg.topo_order()
        bit: dict[str, int] = {}
        names: list[str] = []

        def bits(variables: Any) -> int:
            out = 0
            for name in variables:
                b = bit.get(name)
                if b is None:
                    b = bit[name] = 1 << len(names)
                    names.append(name)
                out |= b
            return out

        use = {offset: bits(var_use_map[offset]) for offset in var_use_map}
        defs = {offset: bits(var_def_map[offset]) for offset in var_def_map}
        # numba's def_reach: what is defined or used in a block reaching each block.
        reach: defaultdict[Any, int] = defaultdict(int)
        succ = {offset: [out for out, _ in cfg.successors(offset)] for offset in topo_order}
        changed = True
        while changed:
            changed = False
            for offset in topo_order:
                value = reach[offset] | defs[offset] | use[offset]
                if value != reach[offset]:
                    reach[offset] = value
                    changed = True
                for out in succ[offset]:
                    merged = reach[out] | value
                    if merged != reach[out]:
                        reach[out] = merged
                        changed = True
        # numba's liveness: a variable live at a block's entry is live at its
        # predecessors' exits where defined before and not defined there.
        live = {offset: use[offset] for offset in blocks}
        preds = {offset: [inc for inc, _ in cfg.predecessors(offset)] for offset in topo_order}
        changed = True
        while changed:
            changed = False
            for offset in reversed(topo_order):
                here = live[offset]
                for inc in preds[offset]:
                    merged = live[inc] | (here & reach[inc] & ~defs[inc])
                    if merged != live[inc]:
                        live[inc] = merged
                        changed = True
        live_map: dict[Any, set[str]] = {}
        for offset, value in live.items():
            variables: set[str] = set()
            while value:
                low = value & -value
                variables.add(names[low.bit_length() - 1])
                value ^= low
            live_map[offset] = variables
        return live_map

    return compute_live_map


def _vars_collector(ir: Any) -> Callable[[Any, Any, list[Any]], None]:
    """A function appending the variables of an IR node's values, as numba lists them.

    ``collect(owner, values, out)`` appends to ``out`` what
    ``owner._rec_list_vars`` gives for each of ``values`` in turn (numba's
    ``Stmt.list_vars`` passes a statement's ``__dict__``, ``Expr.list_vars``
    an expression's ``_kws``): a variable itself, an instruction's
    ``list_vars()``, the variables of a list, tuple or dict's items, nothing
    for anything else. The values met most (variables, ``None``, numba's
    ``UNDEFINED``, builtins, strings, lists and tuples of variables) are
    sorted out by their exact type without a call; the rest go through the
    same tests as numba's, in the same order.
    """
    var_class, inst_class = ir.Var, ir.Inst
    containers = (list, tuple, dict)
    # Exact types that are none of Var, Inst, list, tuple, dict: numba lists nothing for them.
    leaves = frozenset({
        str, int, float, bool, type(None), type(ir.UNDEFINED), ir.Loc,
        type(len), type(_vars_collector),
    })  # fmt: skip

    def collect(owner: Any, values: Any, out: list[Any]) -> None:
        for item in values:
            item_class = type(item)
            if item_class is var_class:
                out.append(item)
            elif item_class in leaves:
                continue
            elif item_class is list or item_class is tuple:
                for sub in item:
                    if type(sub) is var_class:
                        out.append(sub)
                    else:
                        out.extend(owner._rec_list_vars(sub))
            elif isinstance(item, var_class):
                out.append(item)
            elif isinstance(item, inst_class):
                out.extend(item.list_vars())
            elif isinstance(item, containers):
                out.extend(owner._rec_list_vars(item))

    return collect


def _use_defs_function(
    numba_use_defs: Callable[[Any], Any], ir: Any, extensions: dict[Any, Any], result: Any
) -> Callable[[Any], Any]:
    """``analysis.compute_use_defs`` listing each statement's variables once, call-free.

    numba finds the variables each block uses and defines (for its liveness
    and variable deletions, after every pass that changes the IR: 2,147
    times in ``navkit warmup``) by listing the variables of every statement,
    and those of an assignment's value a second time, each list made by a
    recursive call per value of the statement (0.88 s of the whole warm-up).
    Here an assignment's value is listed once (its variables, then the
    target's, as numba's listing of the statement gives them) and the
    statements and expressions that list their variables as numba's ``Stmt``
    and ``Expr`` do are listed by :func:`_vars_collector`: the same names
    added to the same sets in the same order (compared at each call of
    ``navkit warmup``: equal and in the same iteration order). Statements of
    other kinds (an extension's, a class listing its variables otherwise) go
    through numba's own steps; an assignment of a value numba does not know
    goes to numba's function, which raises its own error.
    """
    assign_class, expr_class, var_class, loc_class, inst_class = (
        ir.Assign, ir.Expr, ir.Var, ir.Loc, ir.Inst,
    )  # fmt: skip
    no_vars = (ir.Arg, ir.Const, ir.Global, ir.FreeVar)
    no_vars_exact = frozenset(no_vars)
    stmt_list_vars, expr_list_vars = ir.Stmt.list_vars, ir.Expr.list_vars
    assign_fields = ("value", "target", "loc")
    collect = _vars_collector(ir)

    def compute_use_defs(blocks: Any) -> Any:
        var_use_map: dict[Any, set[str]] = {}
        var_def_map: dict[Any, set[str]] = {}
        # Per statement class: whether it lists its variables as numba's Stmt does.
        listed_as_stmt: dict[type, bool] = {}
        rec_list_vars = inst_class._rec_list_vars
        expr_plain = (
            expr_class.list_vars is expr_list_vars and expr_class._rec_list_vars is rec_list_vars
        )
        for offset, ir_block in blocks.items():
            use_set: set[str] = set()
            def_set: set[str] = set()
            var_use_map[offset], var_def_map[offset] = use_set, def_set
            for stmt in ir_block.body:
                cls = type(stmt)
                if cls in extensions:
                    extensions[cls](stmt, use_set, def_set)
                    continue
                plain = listed_as_stmt.get(cls)
                if plain is None:
                    plain = listed_as_stmt[cls] = (
                        cls.list_vars is stmt_list_vars and cls._rec_list_vars is rec_list_vars
                    )
                fields = stmt.__dict__
                if cls is assign_class and plain and tuple(fields) == assign_fields:
                    value, target = fields["value"], fields["target"]
                    if type(target) is var_class and type(fields["loc"]) is loc_class:
                        # numba's listing of the statement: the value's variables, the target.
                        value_class = type(value)
                        if value_class is var_class:
                            value_vars: list[Any] = [value]
                        elif value_class is expr_class and expr_plain:
                            value_vars = []
                            collect(value, value._kws.values(), value_vars)
                        elif value_class in no_vars_exact:
                            value_vars = []
                        elif isinstance(value, inst_class):
                            value_vars = value.list_vars()
                        else:
                            return numba_use_defs(blocks)  # numba's way (and its error)
                        name = target.name
                        if value_class is var_class or isinstance(value, inst_class):
                            if name not in {var.name for var in value_vars}:
                                def_set.add(name)
                        else:
                            def_set.add(name)
                        for var in value_vars:
                            if var.name not in def_set:
                                use_set.add(var.name)
                        if name not in def_set:
                            use_set.add(name)
                        continue
                # numba's own steps
                if isinstance(stmt, assign_class):
                    value = stmt.value
                    if isinstance(value, inst_class):
                        rhs_set: Any = {var.name for var in value.list_vars()}
                    elif isinstance(value, var_class):
                        rhs_set = {value.name}
                    elif isinstance(value, no_vars):
                        rhs_set = ()
                    else:
                        return numba_use_defs(blocks)  # numba's error
                    if stmt.target.name not in rhs_set:
                        def_set.add(stmt.target.name)
                if plain:
                    stmt_vars: list[Any] = []
                    collect(stmt, fields.values(), stmt_vars)
                else:
                    stmt_vars = stmt.list_vars()
                for var in stmt_vars:
                    if var.name not in def_set:
                        use_set.add(var.name)
        return result(usemap=var_use_map, defmap=var_def_map)

    return compute_use_defs


def _dead_maps_function(numba_dead_maps: Callable[..., Any], result: Any) -> Callable[..., Any]:
    """``analysis.compute_dead_maps`` checking its cover of the live variables in place.

    numba works out where each variable dies (after every pass that changes
    the IR: 1,964 times in ``navkit warmup``, 0.42 s), then checks that every
    live variable dies somewhere by four unions of all blocks' sets, each
    union building a new set per block (``reduce(operator.or_, ...)``): work
    growing as blocks times variables. Here the dead variables are gathered
    in one set updated in place and each block's live set tested against it;
    the maps themselves are made by numba's steps, the same sets built in
    the same order. Should a live variable die nowhere, numba's own function
    is called, which raises its own error.
    """

    def compute_dead_maps(cfg: Any, blocks: Any, live_map: Any, var_def_map: Any) -> Any:
        escaping_dead_map: defaultdict[Any, set[str]] = defaultdict(set)
        internal_dead_map: defaultdict[Any, set[str]] = defaultdict(set)
        exit_dead_map: defaultdict[Any, set[str]] = defaultdict(set)
        for offset, ir_block in blocks.items():
            cur_live_set = live_map[offset] | var_def_map[offset]
            outgoing_live_map = {out: live_map[out] for out, _ in cfg.successors(offset)}
            terminator_liveset = {var.name for var in ir_block.terminator.list_vars()}
            combined_liveset: set[str] = set()
            for live in outgoing_live_map.values():
                combined_liveset |= live
            combined_liveset |= terminator_liveset
            internal_set = cur_live_set - combined_liveset
            internal_dead_map[offset] = internal_set
            escaping_live_set = cur_live_set - internal_set
            for out, new_live_set in outgoing_live_map.items():
                new_live_set = new_live_set | var_def_map[out]
                escaping_dead_map[out] |= escaping_live_set - new_live_set
            if not outgoing_live_map:
                exit_dead_map[offset] = terminator_liveset
        dead_vars: set[str] = set()
        for dead_map in (internal_dead_map, escaping_dead_map, exit_dead_map):
            for dead in dead_map.values():
                dead_vars |= dead
        for live in live_map.values():
            if not live <= dead_vars and cfg.exit_points():
                return numba_dead_maps(cfg, blocks, live_map, var_def_map)  # numba's error
        combined = {k: internal_dead_map[k] | escaping_dead_map[k] for k in blocks}
        return result(internal=internal_dead_map, escaping=escaping_dead_map, combined=combined)

    return compute_dead_maps


def _numbas_own(owner: Any, name: str, names: tuple[str, ...] | None = None) -> Any:
    """``owner``'s own attribute ``name`` if it is numba's function of that name, else None.

    numba's: defined in a ``numba.`` module under the name numba gives it
    (not someone's replacement); with ``names``, its code reads exactly
    those global and attribute names (the shape the shortcut assumes).
    """
    if owner is None:
        return None
    function = vars(owner).get(name)
    code = getattr(function, "__code__", None)
    if code is None or not str(getattr(function, "__module__", "")).startswith("numba."):
        return None
    qualname = name if isinstance(owner, type(importlib)) else f"{owner.__name__}.{name}"
    if function.__qualname__ != qualname:
        return None
    if names is not None and code.co_names != names:
        return None
    return function


#: numba's modules that import the analyses by name (those loaded are patched too).
_IMPORTERS = (
    "numba.core.ir_utils", "numba.core.lowering", "numba.core.transforms",
    "numba.core.untyped_passes", "numba.core.inline_closurecall", "numba.parfors.parfor",
)  # fmt: skip


def _imported_by_name(numba_function: Any, name: str, ours: Any) -> list[tuple[Any, str, Any]]:
    """(module, name, ours) for each loaded numba module holding ``numba_function`` as ``name``."""
    out: list[tuple[Any, str, Any]] = []
    for module_name in _IMPORTERS:
        module = sys.modules.get(module_name)
        if module is not None and vars(module).get(name) is numba_function:
            out.append((module, name, ours))
    return out


def _replacements() -> list[tuple[Any, str, Any]]:
    """(owner, attribute, replacement) for the numba installed, as far as it has them."""
    out: list[tuple[Any, str, Any]] = []
    functions: Any = importlib.import_module("numba.core.types.functions")
    function_class = getattr(functions, "Function", None)
    base_function = getattr(functions, "BaseFunction", None)
    target_extension: Any = importlib.import_module("numba.core.target_extension")
    get_local_target = getattr(target_extension, "get_local_target", None)
    if (
        function_class is not None
        and base_function is not None
        and get_local_target is not None
        and "get_call_type" in vars(base_function)
        and "get_call_type" not in vars(function_class)
    ):
        numba_get_call_type = function_class.get_call_type
        out.append((
            function_class, "get_call_type",
            _call_type_method(function_class, numba_get_call_type, get_local_target),
        ))  # fmt: skip
    ir: Any = importlib.import_module("numba.core.ir")
    var_class, inst_class = getattr(ir, "Var", None), getattr(ir, "Inst", None)
    if var_class is not None and inst_class is not None and "_rec_list_vars" in vars(inst_class):
        out.append((inst_class, "_rec_list_vars", _list_vars_method(var_class, inst_class)))
    analysis: Any = importlib.import_module("numba.core.analysis")
    numba_live_map = vars(analysis).get("compute_live_map")
    # Only where numba's own sweeps follow the topological order: the bits follow them.
    if callable(numba_live_map) and "topo_order" in getattr(
        getattr(numba_live_map, "__code__", None), "co_names", ()
    ):
        ours = _live_map_function(numba_live_map)
        out.append((analysis, "compute_live_map", ours))
        ir_utils: Any = importlib.import_module("numba.core.ir_utils")
        if vars(ir_utils).get("compute_live_map") is numba_live_map:  # imported by name
            out.append((ir_utils, "compute_live_map", ours))
    use_defs = _numbas_own(analysis, "compute_use_defs")
    if (
        use_defs is not None
        and var_class is not None
        and inst_class is not None
        and _numbas_own(inst_class, "_rec_list_vars") is not None
        and all(
            hasattr(ir, name) for name in ("Assign", "Loc", "Arg", "Const", "Global", "FreeVar")
        )
        and isinstance(getattr(ir, "UNDEFINED", None), getattr(ir, "UndefinedType", ()))
        and _numbas_own(getattr(ir, "Stmt", None), "list_vars", ("_rec_list_vars", "__dict__"))
        is not None
        and _numbas_own(getattr(ir, "Expr", None), "list_vars", ("_rec_list_vars", "_kws"))
        is not None
        and isinstance(vars(analysis).get("ir_extension_usedefs"), dict)
        and callable(vars(analysis).get("_use_defs_result"))
    ):
        ours_use_defs = _use_defs_function(
            use_defs, ir, analysis.ir_extension_usedefs, analysis._use_defs_result
        )
        out.append((analysis, "compute_use_defs", ours_use_defs))
        out += _imported_by_name(use_defs, "compute_use_defs", ours_use_defs)
    dead_maps = _numbas_own(analysis, "compute_dead_maps")
    if dead_maps is not None and callable(vars(analysis).get("_dead_maps_result")):
        ours_dead_maps = _dead_maps_function(dead_maps, analysis._dead_maps_result)
        out.append((analysis, "compute_dead_maps", ours_dead_maps))
        out += _imported_by_name(dead_maps, "compute_dead_maps", ours_dead_maps)
    base: Any = importlib.import_module("numba.core.base")
    base_context = getattr(base, "BaseContext", None)
    if callable(vars(base).get("_has_loc")):
        out.append((base, "_has_loc", _has_loc_function(base._has_loc)))
    if base_context is not None and "get_abi_sizeof" in vars(base_context):
        out.append((base_context, "get_abi_sizeof", _abi_size_method(base_context.get_abi_sizeof)))
    targetconfig: Any = importlib.import_module("numba.core.targetconfig")
    target_config = getattr(targetconfig, "TargetConfig", None)
    if target_config is not None and "__eq__" in vars(target_config):
        new_hash, new_eq = _flag_methods(target_config)
        out += [(target_config, "__hash__", new_hash), (target_config, "__eq__", new_eq)]
    errors: Any = importlib.import_module("numba.core.errors")
    scheme_class = getattr(errors, "HighlightColorScheme", None)  # absent: no colorama
    if scheme_class is not None and hasattr(errors, "Style"):
        scheme = errors.termcolor()
        if type(scheme) is scheme_class and "_markup" not in vars(scheme):
            out.append((scheme, "_markup", _markup_method(errors)))
    return out


def _switch_on() -> None:
    # Made afresh each time (a few closures, once per outermost navkit compile):
    # they fall back on the methods in place now, whoever installed those.
    try:
        replacements = _replacements()
    except (ImportError, AttributeError, TypeError):  # a numba laid out otherwise: as it is
        return
    for owner, name, ours in replacements:
        replaced = vars(owner).get(name, _MISSING)
        setattr(owner, name, ours)
        _SAVED.append((owner, name, ours, replaced))


def _switch_off() -> None:
    while _SAVED:
        owner, name, ours, replaced = _SAVED.pop()
        if vars(owner).get(name, _MISSING) is not ours:  # replaced meanwhile: theirs
            continue
        if replaced is _MISSING:
            delattr(owner, name)
        else:
            setattr(owner, name, replaced)


def begin() -> None:
    """Count a navkit compile in; the first of those under way switches the shortcuts on.

    Examples
    --------
    >>> from navkit._shared import compile_shortcuts
    >>> from navkit._shared.jit import load_numba
    >>> load_numba()
    >>> compile_shortcuts.begin()
    >>> compile_shortcuts.active()
    True
    >>> compile_shortcuts.end()
    >>> compile_shortcuts.active()
    False
    """
    global _COUNT
    with _LOCK:
        if _COUNT == 0 and ENABLED:
            _switch_on()
        _COUNT += 1
        _THREAD.count = getattr(_THREAD, "count", 0) + 1


def end() -> None:
    """Count one out; the last to end puts numba's own methods back.

    Examples
    --------
    >>> from navkit._shared import compile_shortcuts
    >>> compile_shortcuts.begin()
    >>> compile_shortcuts.end()
    >>> compile_shortcuts.active()
    False
    """
    global _COUNT
    with _LOCK:
        _COUNT = max(_COUNT - 1, 0)
        _THREAD.count = max(getattr(_THREAD, "count", 0) - 1, 0)
        if _COUNT == 0:
            _switch_off()


def active() -> bool:
    """Whether the shortcuts are switched on now (a navkit compile is under way).

    Examples
    --------
    >>> from navkit._shared import compile_shortcuts
    >>> compile_shortcuts.active()
    False
    """
    with _LOCK:
        return bool(_SAVED)


def _after_fork_in_child() -> None:
    """Keep only the forking thread's count; with none, numba's own methods are back.

    :data:`_LOCK` is taken across a fork by :mod:`navkit._shared.compile_gc`'s
    fork hooks (which import this module), under their hold of signals: taken
    and let go here, outside it, a Ctrl-C in the after hook (a second one, the
    first having cut compile_gc's before hook short) left it held for good
    (review 37).
    """
    global _LOCK, _COUNT
    _LOCK = threading.RLock()  # the parent's is held, by this thread's twin
    _COUNT = getattr(_THREAD, "count", 0)
    if _COUNT == 0:
        _switch_off()


if hasattr(os, "register_at_fork"):  # not on Windows, which cannot fork
    os.register_at_fork(after_in_child=_after_fork_in_child)
