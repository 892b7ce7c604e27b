from ._rangefill import Mesh as Mesh
from ._rangefill import ProcessingError as ProcessingError
from ._rangefill import __version__ as __version__
from ._rangefill import backends as backends
from ._rangefill import fill_depth as fill_depth
from ._rangefill import filler_names as filler_names
from ._rangefill import holes as holes
from ._rangefill import inpaint as inpaint
from ._rangefill import read_depth as read_depth
from ._rangefill import read_mesh as read_mesh
from ._rangefill import repair as repair
from ._rangefill import write_depth as write_depth
from ._rangefill import write_mesh as write_mesh

__all__: list[str]
