"""Where the project's files are, whatever the working directory.

    from hhneck.paths import project_root, project_path
    project_root()                                  # the hhneck checkout
    project_path("input", "head_neck_54dof.inp")    # a file of it

The project is the checkout that holds this package (python/hhneck/ in
it), or the directory named by the environment variable HHNECK_ROOT (for
a copy of the package installed elsewhere). Shipped decks, the reference
data (reference/) and the documents the tools rewrite (docs/) are found
there, never relative to the working directory. find_project(start) is the
checkout that holds a directory (the one fpm builds in, hhneck.run)."""
import os

ENV = "HHNECK_ROOT"


def is_project(d):
    """True when directory `d` holds the hhneck fpm.toml (name = "hhneck")."""
    toml = os.path.join(d, "fpm.toml")
    if not os.path.isfile(toml):
        return False
    with open(toml) as f:
        return any(line.replace(" ", "").startswith('name="hhneck"') for line in f)


def find_project(start):
    """The hhneck project that holds directory `start`: the nearest
    directory upward with the hhneck fpm.toml; None outside one."""
    d = os.path.abspath(start)
    while not is_project(d):
        parent = os.path.dirname(d)
        if parent == d:
            return None
        d = parent
    return d


def project_root():
    """The project's top directory: $HHNECK_ROOT when set, else the checkout
    that holds this package. Raises FileNotFoundError when $HHNECK_ROOT is
    not the project, or when the package lies outside one and HHNECK_ROOT
    is not set."""
    given = os.environ.get(ENV)
    if given:
        if not is_project(given):
            raise FileNotFoundError("%s=%s: no hhneck fpm.toml there" % (ENV, given))
        return os.path.abspath(given)
    root = find_project(os.path.dirname(os.path.abspath(__file__)))
    if root is None:
        raise FileNotFoundError("the hhneck package at %s lies outside the project; set %s to the project's "
                                "top directory" % (os.path.dirname(os.path.abspath(__file__)), ENV))
    return root


def project_path(*parts):
    """A path inside the project: project_path("reference", "nbdl_15g")."""
    return os.path.join(project_root(), *parts)
