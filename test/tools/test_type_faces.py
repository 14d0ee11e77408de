#!/usr/bin/env python3
"""Every body type of the core's description has every face, or a test named after the type and the face fails:
- its Python spec (sim_tools.SPECS), its look in scripts/plot_run.py (TYPES), its random change in
  scripts/soak_driver.py (CHANGES) and its entry in web/types.js (BODY_TYPES), each table read from its file
  (parsed, not run: plot_run needs matplotlib, types.js a browser), with no row for a type the description lacks;
- the files docs/DESIGN.md's table ("A body type") lists: each of the type's own files (the example type's
  name replaced by the type's), each shared file naming it (a table above through its row; CMakeLists.txt
  building its own sources, message and .cfg);
- no file outside that table lists the types (names two of them or more), but the few of ALLOWED, each with
  its reason.
The checks run on a made-up type too, which must fail each of them: none of them passes by construction.
Usage: test_type_faces.py   (with the package's devel space sourced: the description, body_types.json)"""
import ast
import os
import re
import unittest
from dataclasses import dataclass
from typing import Callable, Dict, List, NamedTuple, Optional, Set

from rigid_body_sim import description, sim_tools

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
TYPES = list(description.body_types())
MADE_UP = "wobbler"  # a type no face has: every check must find it missing


def text_of(path: str) -> str:
    with open(os.path.join(ROOT, path), encoding="utf-8") as f:
        return f.read()


def capitalized(type_name: str) -> str:
    """<Type>: as sim_tools.state_message finds <Type>State."""
    return type_name.capitalize()


# --- the tables of the Python tools and the page ------------------------------------------------------------
def python_table_keys(path: str, table: str) -> Set[str]:
    """The keys of the dict literal assigned to `table` at the top of a Python file: a string, or a spec's
    TYPE (`RodSpec.TYPE`, read from sim_tools)."""
    tree = ast.parse(text_of(path))
    for node in tree.body:
        target = node.targets[0] if isinstance(node, ast.Assign) else getattr(node, "target", None)
        value = getattr(node, "value", None)
        if not (isinstance(target, ast.Name) and target.id == table and isinstance(value, ast.Dict)):
            continue
        keys = set()
        for key in value.keys:
            if isinstance(key, ast.Constant) and isinstance(key.value, str):
                keys.add(key.value)
            elif (isinstance(key, ast.Attribute) and key.attr == "TYPE" and isinstance(key.value, ast.Name)
                  and hasattr(sim_tools, key.value.id)):
                keys.add(str(getattr(sim_tools, key.value.id).TYPE))
            else:
                raise AssertionError(f"{path}: a key of {table} that is neither a string nor a spec's TYPE: "
                                     f"{ast.dump(key) if key else '**'}")
        return keys
    raise AssertionError(f"{path} assigns no dict literal to {table}")


def js_object_keys(path: str, name: str) -> Set[str]:
    """The keys of the object literal `const <name> = {...}` of a script: its top level's `key:` (strings,
    template literals and comments skipped)."""
    text = text_of(path)
    found = re.search(r"\bconst\s+" + name + r"\s*=\s*\{", text)
    if not found:
        raise AssertionError(f"{path} declares no object `const {name} = {{`")
    i, depth, keys, expect_key = found.end(), 1, set(), True
    while depth:
        c = text[i]
        if text.startswith("//", i):
            i = text.index("\n", i)
            continue
        if text.startswith("/*", i):
            i = text.index("*/", i) + 2
            continue
        if c in "\"'`":
            end = i + 1
            while text[end] != c:
                end += 2 if text[end] == "\\" else 1
            if depth == 1 and expect_key and re.match(r"\s*:", text[end + 1:]):
                keys.add(text[i + 1:end])
            i, expect_key = end + 1, False
            continue
        word = re.match(r"[A-Za-z_$][\w$]*", text[i:])
        if word:
            if depth == 1 and expect_key and re.match(r"\s*:", text[i + word.end():]):
                keys.add(word.group())
            i, expect_key = i + word.end(), False
            continue
        if c in "{[(":
            depth += 1
        elif c in "}])":
            depth -= 1
        elif c == "," and depth == 1:
            expect_key = True
        i += 1
    return keys


class Face(NamedTuple):
    """A table that says what one face (the tools, the page) knows of each type: a row a type."""
    slug: str  # in the generated tests' names
    what: str
    path: str
    table: str
    keys: Callable[[], Set[str]]


FACES = [
    Face("python_spec", "Python spec (a class with its TYPE in SPECS)", "src/rigid_body_sim/sim_tools.py", "SPECS",
         lambda: set(sim_tools.SPECS)),
    Face("plot_look", "look in plot_run", "scripts/plot_run.py", "TYPES",
         lambda: python_table_keys("scripts/plot_run.py", "TYPES")),
    Face("soak_change", "random change in soak_driver", "scripts/soak_driver.py", "CHANGES",
         lambda: python_table_keys("scripts/soak_driver.py", "CHANGES")),
    Face("web_entry", "entry on the web page", "web/types.js", "BODY_TYPES",
         lambda: js_object_keys("web/types.js", "BODY_TYPES")),
]
FACE_FILES = {face.path: face for face in FACES}


def missing_face(face: Face, type_name: str) -> str:
    """"" when the type has its row in the face's table, else the line a failure says."""
    if type_name in face.keys():
        return ""
    return f"body type '{type_name}' has no {face.what}: add its row to {face.table} in {face.path}"


# --- docs/DESIGN.md's table of a type's files ---------------------------------------------------------------
@dataclass(frozen=True)
class Recipe:
    example: str  # the type whose files the table names
    own: List[str]  # the example's own files
    shared: List[str]

    def own_files(self, type_name: str) -> List[str]:
        """Another type's own files: its name for the example's, capitalized for capitalized."""
        return [path.replace(self.example, type_name).replace(capitalized(self.example), capitalized(type_name))
                for path in self.own]


def read_recipe() -> Recipe:
    design = text_of("docs/DESIGN.md")
    start = design.index("- **A body type**:")
    section = design[start:design.index("\n## ", start)]
    example = re.search(r"the (\w+)'s is the example", section)
    assert example, "DESIGN.md's body type entry names no example type (\"the block's is the example\")"
    own: List[str] = []
    shared: List[str] = []
    for line in section.splitlines():
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
        if not line.strip().startswith("| `") or len(cells) < 3:
            continue
        files = re.findall(r"`([^`]+)`", cells[0])
        assert cells[1] in ("its own", "shared"), f"DESIGN.md: '{cells[1]}' in {line!r}: its own or shared"
        (own if cells[1] == "its own" else shared).extend(files)
    return Recipe(example.group(1), own, shared)


# What names a type in code: its classes and messages, its name quoted, an object's key, its files' names.
def type_names_in(text: str, type_name: str) -> bool:
    t, big = re.escape(type_name), re.escape(capitalized(type_name))
    return any(re.search(pattern, text, re.M) for pattern in (
        rf"\b{big}(Type|Spec|Config|State|Params|Initial|Motion|Rviz|Reconfigure|Run|Mode)\b",
        rf"[\"']{t}[\"']", rf"^\s*{t}\s*:", rf"\b{t}(_type|_ros|_rviz)?\.(h|cpp)\b", rf"\bforeach\(cfg [^)]*\b{big}\b"))


def without_comments(path: str, text: str) -> str:
    """Its code: a comment may name any type (C++ and JS //, Python, CMake and shell #)."""
    if path.endswith((".h", ".cpp", ".js")):
        return re.sub(r"(^|\s)//.*", "", text)
    if path.endswith((".py", ".txt", ".cfg", ".msg", ".srv")) or "." not in os.path.basename(path):
        return re.sub(r"(^|\s)#(?!include).*", "", text)
    return text


def missing_in_shared(recipe: Recipe, path: str, type_name: str) -> str:
    """"" when a shared file of the table names the type as it should, else the line a failure says."""
    if path in FACE_FILES:
        return missing_face(FACE_FILES[path], type_name)
    code = without_comments(path, text_of(path))
    if os.path.basename(path) == "CMakeLists.txt":
        built = [f for f in recipe.own_files(type_name) if f.endswith((".cpp", ".msg", ".cfg"))]
        unbuilt = [f for f in built if not re.search(r"(^|[\s/])" + re.escape(os.path.basename(f)) + r"\b", code, re.M)]
        if unbuilt:
            return f"body type '{type_name}': {path} does not build {', '.join(unbuilt)}"
    if not type_names_in(code, type_name):
        return f"body type '{type_name}' is not named in {path}, a shared file of DESIGN.md's table"
    return ""


# --- files that list the types outside the table ------------------------------------------------------------
SEARCHED = ("include", "src", "scripts", "bench", "web", "examples", "launch", "rviz", "msg", "srv", "cfg",
            "CMakeLists.txt", "package.xml", "setup.py")
# Files outside DESIGN.md's table that name two types or more, none a table a new type needs a row in:
ALLOWED: Dict[str, str] = {
    # The bench times the rod's and the roller's steps, the text's two examples, by name.
    "bench/bench_core.cpp": "benchmarks of two particular types",
    # An example of the Python module: the text's rod and rollers.
    "examples/python/text_vs_core.py": "an example of particular bodies",
    # The docs' figures: numbers of particular runs of the docs (the demo's rod, the bowler).
    "scripts/doc_figures.py": "the docs' figures of particular bodies",
    # Installed for other packages' tests: it includes the messages of its documented examples, and a test of
    # any other type includes its own (its docstring says so).
    "include/rigid_body_sim/testing/sim_fixture.h": "the messages of its examples",
    # Its docstrings name the messages of its examples, as sim_fixture.h's.
    "src/rigid_body_sim/testing.py": "its docstrings' examples",
}


def searched_files() -> List[str]:
    paths = []
    for top in SEARCHED:
        if os.path.isfile(os.path.join(ROOT, top)):
            paths.append(top)
            continue
        for folder, _, names in os.walk(os.path.join(ROOT, top)):
            paths += [os.path.relpath(os.path.join(folder, name), ROOT) for name in names]
    return sorted(paths)


def types_named(path: str, type_names: List[str]) -> List[str]:
    code = without_comments(path, text_of(path))
    return [t for t in type_names if type_names_in(code, t)]


def listing_files(type_names: List[str], recipe: Recipe, paths: Optional[List[str]] = None,
                  read: Callable[[str], str] = text_of) -> Dict[str, List[str]]:
    """The files outside the table (and ALLOWED) that name two of `type_names` or more, with those: of the
    searched folders, or of `paths` as `read` gives them."""
    table = set(recipe.shared) | {f for t in type_names for f in recipe.own_files(t)}
    found = {}
    for path in searched_files() if paths is None else paths:
        if path in table or path in ALLOWED:
            continue
        try:
            code = without_comments(path, read(path))
        except UnicodeDecodeError:  # an image, a font
            continue
        named = [t for t in type_names if type_names_in(code, t)]
        if len(named) >= 2:
            found[path] = named
    return found


# --- the tests ---------------------------------------------------------------------------------------------
class Faces(unittest.TestCase):
    """Generated below: test_<face>_of_<type> for each face and type of the description."""

    def test_each_table_has_only_the_descriptions_types(self) -> None:
        for face in FACES:
            self.assertEqual(face.keys() - set(TYPES), set(),
                             f"{face.path}: rows in {face.table} for types the description does not have")

    def test_each_spec_is_its_types(self) -> None:
        for type_name in TYPES:
            spec = sim_tools.body_spec({"bodies": {"b": {"type": type_name}}}, "b")
            self.assertEqual(spec.TYPE, type_name)


def face_test(face: Face, type_name: str) -> Callable[[Faces], None]:
    def test(self: Faces) -> None:
        line = missing_face(face, type_name)
        if line:
            self.fail(line)
    return test


for _face in FACES:
    for _type in TYPES:
        setattr(Faces, f"test_{_face.slug}_of_{_type}", face_test(_face, _type))


class RecipeFiles(unittest.TestCase):
    """Generated below: test_own_files_of_<type> and test_shared_files_name_<type>."""

    def test_the_table_is_read(self) -> None:
        recipe = read_recipe()
        self.assertIn(recipe.example, TYPES)
        self.assertGreaterEqual(len(recipe.own), 8, recipe.own)
        self.assertGreaterEqual(len(recipe.shared), 5, recipe.shared)
        for path in recipe.own:
            self.assertIn(recipe.example, path.lower(), f"DESIGN.md: {path}, its own, does not name the example")
        for path in recipe.shared:
            self.assertNotIn(recipe.example, path.lower(), f"DESIGN.md: {path}, shared, names the example")
        for face in FACES:
            self.assertIn(face.path, recipe.shared, f"DESIGN.md's table lacks {face.path} ({face.table})")

    def test_no_other_file_lists_the_types(self) -> None:
        self.assertEqual(listing_files(TYPES, read_recipe()), {},
                         "files outside DESIGN.md's table that list body types: add them to the table (a new "
                         "type needs its row there) or, with a reason, to ALLOWED in this test")

    def test_every_allowed_file_still_lists_types(self) -> None:
        for path, why in ALLOWED.items():
            self.assertTrue(os.path.isfile(os.path.join(ROOT, path)), f"ALLOWED names {path}, which is gone")
            self.assertGreaterEqual(len(types_named(path, TYPES)), 2, f"{path} ({why}) no longer lists types")


def own_files_test(type_name: str) -> Callable[[RecipeFiles], None]:
    def test(self: RecipeFiles) -> None:
        absent = [f for f in read_recipe().own_files(type_name) if not os.path.isfile(os.path.join(ROOT, f))]
        self.assertEqual(absent, [], f"body type '{type_name}' lacks files of its own that DESIGN.md's table lists")
    return test


def shared_files_test(type_name: str) -> Callable[[RecipeFiles], None]:
    def test(self: RecipeFiles) -> None:
        recipe = read_recipe()
        missing = [m for m in (missing_in_shared(recipe, path, type_name) for path in recipe.shared) if m]
        if missing:
            self.fail("; ".join(missing))
    return test


for _type in TYPES:
    setattr(RecipeFiles, f"test_own_files_of_{_type}", own_files_test(_type))
    setattr(RecipeFiles, f"test_shared_files_name_{_type}", shared_files_test(_type))


class AMadeUpType(unittest.TestCase):
    """A type no file has fails every check above, each saying what is missing where."""

    def test_every_face_is_missing(self) -> None:
        for face in FACES:
            line = missing_face(face, MADE_UP)
            self.assertIn(f"'{MADE_UP}'", line)
            self.assertIn(face.path, line)

    def test_every_own_file_is_missing(self) -> None:
        recipe = read_recipe()
        for path in recipe.own_files(MADE_UP):
            self.assertIn(MADE_UP, path.lower())
            self.assertFalse(os.path.exists(os.path.join(ROOT, path)), path)

    def test_every_shared_file_lacks_it(self) -> None:
        recipe = read_recipe()
        for path in recipe.shared:
            line = missing_in_shared(recipe, path, MADE_UP)
            self.assertIn(f"'{MADE_UP}'", line)
            self.assertIn(path, line)

    def test_the_tools_refuse_it_in_one_line(self) -> None:
        with self.assertRaises(sim_tools.MissingFace) as refused:
            sim_tools.body_spec({"bodies": {"b": {"type": MADE_UP}}}, "b")
        self.assertIn(f"body type '{MADE_UP}' has no Python spec", str(refused.exception))
        self.assertIn("src/rigid_body_sim/sim_tools.py", str(refused.exception))
        self.assertNotIn("\n", str(refused.exception))

    def test_a_table_of_it_outside_the_recipe_is_found(self) -> None:
        """A file outside the table that lists it beside a real type, in a dict or an object, or a comment."""
        files = {"scripts/looks.py": f'LOOKS = {{{TYPES[0]!r}: 1, "{MADE_UP}": 2}}',
                 "web/looks.js": f"const LOOKS = {{\n  {TYPES[0]}: {{}},\n  {MADE_UP}: {{}},\n}};",
                 "scripts/said.py": f"# {TYPES[0]!r} and {MADE_UP!r}, in a comment"}
        found = listing_files(TYPES + [MADE_UP], read_recipe(), list(files), files.__getitem__)
        self.assertEqual(found, {"scripts/looks.py": [TYPES[0], MADE_UP], "web/looks.js": [TYPES[0], MADE_UP]})


if __name__ == "__main__":
    unittest.main()
