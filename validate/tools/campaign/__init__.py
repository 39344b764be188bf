"""Campaigns: overturning spectra, fragility curves and agreement maps over thousands
of runs, serially or on a Dask cluster (`isorock sweep`, docs/campaigns.md)."""
from .run import CampaignResult, run_campaign, run_cases
from .spec import Case, CampaignSpec, EngineSetting, load_spec, parse_spec

__all__ = ["CampaignResult", "CampaignSpec", "Case", "EngineSetting", "load_spec", "parse_spec",
           "run_campaign", "run_cases"]
