"""The command line of the sample scripts Blender runs (`blender -b --python script.py -- args`).

What follows Blender's "--", and the `<outdir> [names...]` the corpus scripts take. A script puts
samples/blender (its own folder, or the one beside it) on sys.path to import this; Blender adds
none of it. No bpy here: also usable outside Blender.
"""
import os
import sys


def script_args():
    """The arguments after Blender's "--" (empty without one)."""
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


def parse_outdir(script_name):
    """The one argument `<outdir>`, made if missing; exits 2 with the usage otherwise."""
    args = script_args()
    if len(args) != 1:
        print("usage: blender -b --factory-startup --python %s -- <outdir>" % script_name,
              file=sys.stderr)
        sys.exit(2)
    outdir = os.path.abspath(args[0])
    os.makedirs(outdir, exist_ok=True)
    return outdir


def outdir_and_names(args, by_name, usage, kind="scene", default=None):
    """`<outdir> [names...]` from `args`: the output folder (absolute, made if missing) and the
    names asked for (`default`, or all of `by_name` in its order, when none is given). Exits 2
    with `usage` and the known names when there is no outdir or a name is unknown."""
    known = "%ss: %s" % (kind, " ".join(by_name))
    if not args:
        print(usage + "\n" + known, file=sys.stderr)
        sys.exit(2)
    outdir = os.path.abspath(args[0])
    names = args[1:] or list(default if default is not None else by_name)
    unknown = [n for n in names if n not in by_name]
    if unknown:
        print("unknown %s(s): %s\n%s" % (kind, " ".join(unknown), known), file=sys.stderr)
        sys.exit(2)
    os.makedirs(outdir, exist_ok=True)
    return outdir, names


def take_option(args, name, default, convert=int):
    """The value after `name` in `args`, converted, both removed from `args`; `default` when absent."""
    if name not in args:
        return default
    i = args.index(name)
    value = convert(args[i + 1])
    del args[i:i + 2]
    return value
