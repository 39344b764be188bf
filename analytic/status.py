"""How a run ended: one enum every engine's Trajectory carries, with a message beside it
(as scipy's `OdeResult.status` and MuJoCo's rollout do). A `StrEnum`, so the value is the
plain word in JSON, CSV and Parquet, and compares equal to it."""
from __future__ import annotations

from enum import StrEnum


class Status(StrEnum):
    COMPLETED = "completed"      #: reached the end time
    OVERTURNED = "overturned"    #: the block overturned (by the run's overturning rule)
    EVENT_LIMIT = "event-limit"  #: the analytic model stopped after `max_events` events
    FAILED = "failed"            #: the integration or the engine failed, or (analytic, a non-linear isolator) its
    #: energy balance did (limits.ENERGY_BALANCE_LIMIT); the message says why
    SLID = "slid"                #: a contact engine's block slid on its base: not the no-sliding model
    #: the exact model's assumptions broke and it stopped there, saying which (the block would
    #: leave its base, Coulomb friction admits no mode, a landing needs a negative normal
    #: impulse: docs/sliding.md): no answer, and no fault of the integration
    OUTSIDE_MODEL = "outside-model"

    @property
    def ended_normally(self) -> bool:
        """True when the history covers the physics asked for (completed or overturned)."""
        return self in (Status.COMPLETED, Status.OVERTURNED)

    @property
    def is_failure(self) -> bool:
        """True when the run produced no answer to trust (failed, stopped at the event limit, or
        beyond the model's assumptions)."""
        return self in (Status.FAILED, Status.EVENT_LIMIT, Status.OUTSIDE_MODEL)


__all__ = ["Status"]
