"""SubstitutionFailure: the error of a substitution that cannot be performed."""


class SubstitutionFailure(RuntimeError):
    """A substitution could not be performed (missing configuration, package, executable...)."""
