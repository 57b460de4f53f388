"""The parity suite runs the Python module in this interpreter and the CLI (and Octave) as child
processes. In the sanitizer build the interpreter starts with the shared ASan runtime in
LD_PRELOAD (the module needs it); the CLI carries its own, static runtime and refuses to start
beside the shared one ("linked against incompatible ASan runtimes"). The preload has done its work
once this interpreter runs, so the children start without it."""

import os

os.environ.pop("LD_PRELOAD", None)
