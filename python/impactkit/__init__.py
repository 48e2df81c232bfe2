"""impactkit: exact simulation, periodic orbits, continuation and analysis of
multi-degree-of-freedom impact oscillators (Python interface to the C++ library).

The compiled module, impactkit._impactkit, holds every computation; this
package re-exports its names and adds the tables of _tables.py: results as
pandas DataFrames and xarray Datasets, with the command line's column names
(pandas and xarray are optional: only the conversions need them).
"""

from . import _impactkit
from ._impactkit import *  # noqa: F401,F403 -- every public name of the compiled module
from ._impactkit import __version__
from . import _tables

__doc__ = _impactkit.__doc__

SimulationResult = _tables.SimulationResult
SweepResult = _tables.SweepResult
MapResult = _tables.MapResult
BasinsResult = _tables.BasinsResult
simulate = _tables.wrap(_impactkit.simulate, SimulationResult)
sweep = _tables.wrap(_impactkit.sweep, SweepResult, _impactkit.SweepOptions)
parameter_map = _tables.wrap(_impactkit.parameter_map, MapResult, _impactkit.MapOptions)
basins = _tables.wrap(_impactkit.basins, BasinsResult, _impactkit.BasinsOptions)
_tables.add_methods(_impactkit)
