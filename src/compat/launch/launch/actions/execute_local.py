"""ExecuteLocal: upstream's name of the process-running action class."""

from launch.actions.execute_process import ExecuteProcess

# Upstream's ExecuteLocal is the base class of ExecuteProcess; here both names are one class.
ExecuteLocal = ExecuteProcess
