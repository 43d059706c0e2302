"""Every Blender API name the add-on uses, found in its source and checked in the running Blender
(run by test_blender_api_names.py in each Blender):

    ... api_names.py -- [EXTRA.py ...]

The add-on's Python files (and any EXTRA ones) are read as syntax trees, never run. Checked:
- dotted names from Blender's modules (bpy.app.handlers.persistent, bmesh.ops.recalc_face_normals,
  blf.SHADOW, gpu.state.blend_set, mathutils.Vector, ...), resolved attribute by attribute;
- operators, bpy.ops.GROUP.NAME;
- types, bpy.types.NAME, and strings that name one ('GeometryNodeTree', 'ShaderNodeBsdfGlass',
  'NodeSocketGeometry', ...);
- attributes of Blender data whose type follows from the code: bpy.context and bpy.data, a
  `context` argument, `self` in a class derived from a bpy.types class, items of a collection, what
  a collection's new() returns (the type named by a string argument where there is one), a
  pointer's target, local names bound to these;
- enum values: a string assigned to, or compared with, an enum property of such data
  (m.solver = 'EXACT', obj.type == 'MESH'), and a string given to an enum argument of a function
  (modifiers.new(name, 'BOOLEAN'), attributes.new(name, 'BOOLEAN', 'FACE'));
- icons: every `icon='NAME'` keyword, whatever layout it is given to (icons are renamed between
  versions: LIGHTPROBE_GRID is LIGHTPROBE_VOLUME in 4.x, and a panel naming a missing one fails to
  draw).
Prints "CHECKED n" and one "MISSING file:line: what" per name this Blender lacks; exits 1 if any."""

import ast
import importlib
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import installed  # noqa: E402

MODULES = ("bpy", "bmesh", "blf", "gpu", "gpu_extras", "mathutils", "bpy_extras", "addon_utils")
TYPE_NAME_PREFIXES = ("ShaderNode", "GeometryNode", "FunctionNode", "CompositorNode", "NodeSocket", "NodeGroup")
COLLECTION_METHODS = set(dir(bpy.types.bpy_prop_collection)) | {"add", "clear", "move", "remove"}


def descendants():
    """Each RNA type's identifier -> the RNA types derived from it (Modifier -> BooleanModifier, ...)."""
    found = {}
    for name in dir(bpy.types):
        rna = getattr(getattr(bpy.types, name), "bl_rna", None)
        base = rna.base if rna is not None else None
        while base is not None:
            found.setdefault(base.identifier, []).append(rna)
            base = base.base
    return found


ADDON_CLASSES = {}  # the add-on's registered classes by RNA identifier (filled by main)


class Struct:
    """Data of an RNA type (bpy.types.NAME)."""

    def __init__(self, rna):
        self.rna = rna

    def __repr__(self):
        return self.rna.identifier


class Collection:
    """A collection property of an RNA type: its items' type and its own functions (new, remove...)."""

    def __init__(self, prop):
        self.prop = prop

    def __repr__(self):
        return "%s[]" % self.prop.fixed_type.identifier


DESCENDANTS = descendants()
# Context members that are not RNA properties (the screen's and the 3D View's, as documented in
# bpy.context), with the type of what they give.
CONTEXT_MEMBERS = {"active_object": Struct(bpy.types.Object.bl_rna), "object": Struct(bpy.types.Object.bl_rna),
                   "edit_object": Struct(bpy.types.Object.bl_rna),
                   "selected_objects": True, "visible_objects": True, "objects_in_mode": True,
                   "selected_editable_objects": True}

def inherited_from_addon(class_name):
    """What a registered class of the add-on inherits from the add-on's own classes (a mixin such
    as JobOperator): methods and attributes that the class's own source does not show."""
    found = set()
    for cls in ADDON_CLASSES.values():
        if cls.__name__ == class_name:
            for base in cls.__mro__[1:]:
                if base.__module__.startswith(installed.package().__name__ + "."):
                    found |= set(vars(base))
    return found


def python_class(rna):
    return ADDON_CLASSES.get(rna.identifier) or getattr(bpy.types, rna.identifier, None)


class Checker(ast.NodeVisitor):
    def __init__(self, path):
        self.path = path
        self.checked = 0
        self.missing = []
        self.aliases = {}      # local name -> dotted module path ("bpy", "bpy.props.IntProperty")
        self.scopes = [{}]     # name -> Struct / Collection, per function
        self.bases = []        # the bpy.types base of each enclosing class (or None)
        self.own = []          # the names each enclosing class defines (methods, properties, self.X = ...)

    # -- what is found, and what is missing
    def report(self, node, ok, what):
        self.checked += 1
        if not ok:
            self.missing.append("%s:%d: %s" % (self.path, node.lineno, what))

    # -- imports
    def visit_Import(self, node):
        for a in node.names:
            if a.name.split(".")[0] in MODULES:
                self.aliases[(a.asname or a.name).split(".")[0]] = a.name.split(".")[0] if not a.asname else a.name
                self.check_module_path(node, a.name)

    def visit_ImportFrom(self, node):
        if node.level or not node.module or node.module.split(".")[0] not in MODULES:
            return
        for a in node.names:
            dotted = "%s.%s" % (node.module, a.name)
            self.aliases[a.asname or a.name] = dotted
            self.check_module_path(node, dotted)

    def check_module_path(self, node, dotted):
        parts = dotted.split(".")
        try:
            value = importlib.import_module(parts[0])
        except ImportError:
            self.report(node, False, "module %s" % parts[0])
            return
        for i, part in enumerate(parts[1:], 1):
            try:
                value = getattr(value, part)
            except AttributeError:
                try:
                    value = importlib.import_module(".".join(parts[:i + 1]))
                except ImportError:
                    self.report(node, False, ".".join(parts[:i + 1]))
                    return
        self.report(node, True, dotted)

    # -- scopes: functions bind `context`, methods bind `self`
    def visit_ClassDef(self, node):
        base = None
        for b in node.bases:
            dotted = self.dotted(b)
            if dotted and dotted.startswith("bpy.types."):
                base = getattr(bpy.types, dotted.split(".")[2], None)
                self.report(node, base is not None, dotted)
                base = base if base is not None else None
        own = set()
        for n in ast.walk(node):
            if isinstance(n, (ast.FunctionDef, ast.ClassDef)):
                own.add(n.name)
            elif isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store):
                own.add(n.id)
            elif isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name):
                own.add(n.target.id)
            elif (isinstance(n, ast.Attribute) and isinstance(n.ctx, ast.Store)
                  and isinstance(n.value, ast.Name) and n.value.id == "self"):
                own.add(n.attr)
        own |= inherited_from_addon(node.name)
        self.bases.append(base)
        self.own.append(own)
        self.generic_visit(node)
        self.own.pop()
        self.bases.pop()

    def visit_FunctionDef(self, node):
        scope = {}
        names = [a.arg for a in node.args.args]
        if "context" in names:
            scope["context"] = Struct(bpy.types.Context.bl_rna)
        if names[:1] == ["self"] and self.bases and self.bases[-1] is not None:
            scope["self"] = Struct(self.bases[-1].bl_rna)
        self.scopes.append(scope)
        self.generic_visit(node)
        self.scopes.pop()

    visit_AsyncFunctionDef = visit_FunctionDef

    def visit_Assign(self, node):
        self.generic_visit(node)
        kind = self.type_of(node.value)
        for target in node.targets:
            if isinstance(target, ast.Name):
                if kind is not None:
                    self.scopes[-1][target.id] = kind
                else:
                    self.scopes[-1].pop(target.id, None)
            elif isinstance(target, ast.Attribute):
                self.check_enum(target, node.value)

    def visit_Compare(self, node):
        self.generic_visit(node)
        if isinstance(node.left, ast.Attribute):
            for right in node.comparators:
                self.check_enum(node.left, right)

    # -- dotted module names and operators
    def dotted(self, node):
        parts = []
        while isinstance(node, ast.Attribute):
            parts.append(node.attr)
            node = node.value
        if isinstance(node, ast.Name) and node.id in self.aliases:
            return ".".join([self.aliases[node.id]] + parts[::-1])
        return None

    def visit_Attribute(self, node):
        dotted = self.dotted(node)
        if dotted is not None and isinstance(node.ctx, ast.Load):
            self.check_dotted(node, dotted)
            return  # its inner parts are prefixes of this one
        owner = self.type_of(node.value)
        if owner is not None and not self.defined_by_addon(node):
            self.report(node, self.member(owner, node.attr) is not None, "%r.%s" % (owner, node.attr))
        self.generic_visit(node)

    def defined_by_addon(self, node):
        """self.NAME where the add-on's class defines NAME (its own method, property or attribute)."""
        return (isinstance(node.value, ast.Name) and node.value.id == "self" and bool(self.own)
                and node.attr in self.own[-1])

    def check_dotted(self, node, dotted):
        parts = dotted.split(".")
        if parts[:2] == ["bpy", "ops"]:
            if len(parts) >= 4:
                group = getattr(bpy.ops, parts[2])
                self.report(node, parts[3] in dir(group), "bpy.ops.%s.%s" % (parts[2], parts[3]))
            return
        if parts[:2] == ["bpy", "types"] and len(parts) >= 3:
            self.report(node, hasattr(bpy.types, parts[2]), "bpy.types." + parts[2])
            owner = getattr(bpy.types, parts[2], None)
            if owner is not None and len(parts) >= 4 and hasattr(owner, "bl_rna"):
                self.report(node, self.member(Struct(owner.bl_rna), parts[3]) is not None, dotted)
            return
        if parts[:2] in (["bpy", "context"], ["bpy", "data"]):
            kind = Struct(bpy.types.Context.bl_rna if parts[1] == "context" else bpy.types.BlendData.bl_rna)
            for i, part in enumerate(parts[2:], 2):
                nxt = self.member(kind, part)
                self.report(node, nxt is not None, "%r.%s" % (kind, part))
                if not isinstance(nxt, (Struct, Collection)):
                    return
                kind = nxt
            return
        value = importlib.import_module(parts[0])
        for i, part in enumerate(parts[1:], 1):
            if not hasattr(value, part):
                try:
                    value = importlib.import_module(".".join(parts[:i + 1]))
                    continue
                except ImportError:
                    self.report(node, False, ".".join(parts[:i + 1]))
                    return
            value = getattr(value, part)
        self.report(node, True, dotted)

    # -- the type of an expression, where it follows from the code
    def member(self, owner, name):
        """What owner.name is: a Struct, a Collection, True (something else), or None (missing)."""
        if isinstance(owner, Collection):
            srna = owner.prop.srna
            if srna is not None and name in srna.functions:
                return srna.functions[name]
            if srna is not None and name in srna.properties:
                return self.of_property(srna.properties[name])
            return True if name in COLLECTION_METHODS else None
        rna = owner.rna
        if name in rna.properties:
            return self.of_property(rna.properties[name])
        if name in rna.functions:
            return rna.functions[name]
        cls = python_class(rna)
        if cls is not None and hasattr(cls, name):
            return True
        if rna.identifier == "Context" and name in CONTEXT_MEMBERS:
            return CONTEXT_MEMBERS[name]
        for derived in DESCENDANTS.get(rna.identifier, ()):  # obj.data is an ID, a mesh's
            if name in derived.properties:
                return self.of_property(derived.properties[name])
            if name in derived.functions:
                return derived.functions[name]
        return None

    def of_property(self, prop):
        if prop.type == 'POINTER' and prop.fixed_type is not None:
            return Struct(prop.fixed_type)
        if prop.type == 'COLLECTION' and prop.fixed_type is not None:
            return Collection(prop)
        return prop

    def type_of(self, node):
        if isinstance(node, ast.Name):
            for scope in reversed(self.scopes):
                if node.id in scope:
                    return scope[node.id]
            return None
        dotted = self.dotted(node)
        if dotted in ("bpy.context", "bpy.data"):
            return Struct(bpy.types.Context.bl_rna if dotted == "bpy.context" else bpy.types.BlendData.bl_rna)
        if isinstance(node, ast.Attribute):
            owner = self.type_of(node.value)
            kind = self.member(owner, node.attr) if owner is not None else None
            return kind if isinstance(kind, (Struct, Collection)) else None
        if isinstance(node, ast.Subscript):
            owner = self.type_of(node.value)
            if isinstance(owner, Collection) and not isinstance(node.slice, ast.Slice):
                return Struct(owner.prop.fixed_type)
            return None
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
            owner = self.type_of(node.func.value)
            if isinstance(owner, Collection):
                if node.func.attr in ("get", "new", "add"):
                    return self.returned(owner, node)
        return None

    def returned(self, owner, call):
        """The type an item of the collection comes back as, from get/new/add; the type a string
        argument names where it names one (node_groups.new(name, 'GeometryNodeTree'))."""
        for arg in call.args:
            if isinstance(arg, ast.Constant) and isinstance(arg.value, str) and hasattr(bpy.types, arg.value):
                named = getattr(bpy.types, arg.value)
                if hasattr(named, "bl_rna"):
                    return Struct(named.bl_rna)
        srna = owner.prop.srna
        if call.func.attr != "get" and srna is not None and call.func.attr in srna.functions:
            outputs = [p for p in srna.functions[call.func.attr].parameters if p.is_output and p.type == 'POINTER']
            if outputs:
                return Struct(outputs[0].fixed_type)
        return Struct(owner.prop.fixed_type)

    # -- enum values
    def check_enum(self, target, value):
        owner = self.type_of(target.value)
        if owner is None:
            return
        props = self.enum_properties(owner, target.attr)
        for s in self.strings(value):
            what = "%r.%s = '%s'" % (owner, target.attr, s)
            items = {i.identifier for p in props for i in p.enum_items}
            if items:  # else its items are computed at run time
                self.report(target, s in items, what)

    def enum_properties(self, owner, name):
        """The enum properties `name` of owner's type, or of the types derived from it."""
        if not isinstance(owner, Struct):
            return []
        types = [owner.rna] + DESCENDANTS.get(owner.rna.identifier, [])
        return [t.properties[name] for t in types if name in t.properties and t.properties[name].type == 'ENUM']

    def check_enum_item(self, node, prop, value, what):
        items = [i.identifier for i in prop.enum_items]
        if items:  # else its items are computed at run time
            self.report(node, value in items, what)

    def strings(self, node):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            return [node.value]
        if isinstance(node, (ast.Set, ast.Tuple, ast.List)):
            return [e.value for e in node.elts if isinstance(e, ast.Constant) and isinstance(e.value, str)]
        return []

    def visit_Call(self, node):
        self.generic_visit(node)
        if not isinstance(node.func, ast.Attribute):
            return
        owner = self.type_of(node.func.value)
        if owner is None:
            return
        function = self.member(owner, node.func.attr)
        if not isinstance(function, bpy.types.Function):
            return
        params = [p for p in function.parameters if not p.is_output]
        given = list(zip(params, node.args)) + [(p, kw.value) for kw in node.keywords for p in params
                                                 if p.identifier == kw.arg]
        for param, arg in given:
            if param.type == 'ENUM':
                for s in self.strings(arg):
                    if hasattr(bpy.types, s):
                        continue  # a type's name (node_groups.new(name, 'GeometryNodeTree')): checked as one
                    self.check_enum_item(node, param, s, "%r.%s(%s='%s')" % (owner, node.func.attr, param.identifier, s))

    def visit_Constant(self, node):
        if (isinstance(node.value, str) and node.value.startswith(TYPE_NAME_PREFIXES)
                and node.value.isidentifier()):
            self.report(node, hasattr(bpy.types, node.value), "type '%s'" % node.value)


def sources():
    package = os.path.dirname(installed.package().__file__)
    files = [os.path.join(package, "__init__.py")]
    folder = os.path.join(package, "blender")
    files += sorted(os.path.join(here, f) for here, _, names in os.walk(folder) for f in names if f.endswith(".py"))
    extra = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    return [(f, os.path.relpath(f, os.path.dirname(package))) for f in files] + [(f, f) for f in extra]


ICONS = set(bpy.types.UILayout.bl_rna.functions["operator"].parameters["icon"].enum_items.keys())


def missing_icons(tree, shown):
    """"file:line: icon='NAME'" for each icon keyword naming an icon this Blender lacks."""
    return ["%s:%d: icon=%r" % (shown, node.lineno, node.value.value) for node in ast.walk(tree)
            if isinstance(node, ast.keyword) and node.arg == "icon" and isinstance(node.value, ast.Constant)
            and isinstance(node.value.value, str) and node.value.value not in ICONS]


def main():
    installed.enable()
    for cls in importlib.import_module(installed.package().__name__ + ".blender").classes:
        ADDON_CLASSES[cls.bl_rna.identifier] = cls
    checked, missing = 0, []
    for path, shown in sources():
        checker = Checker(shown)
        with open(path) as f:
            tree = ast.parse(f.read(), path)
        checker.visit(tree)
        checked += checker.checked
        missing += checker.missing + missing_icons(tree, shown)
    print("BLENDER %s" % bpy.app.version_string)
    print("CHECKED %d" % checked)
    for line in missing:
        print("MISSING " + line)
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
