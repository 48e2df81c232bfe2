"""impactkit: exact simulation, periodic orbits, continuation and analysis of
multi-degree-of-freedom impact oscillators (Python interface to the C++ library).

The compiled module, impactkit._impactkit, holds every computation; this
package re-exports its names.
"""

from . import _impactkit
from ._impactkit import *  # noqa: F401,F403 -- every public name of the compiled module
from ._impactkit import __version__

__doc__ = _impactkit.__doc__
