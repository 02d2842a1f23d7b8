"""A run against its independent reference, one module per comparison (edge: may import astropy and
spinorbit.references): the scenes declare what they compare, these modules compare it."""
