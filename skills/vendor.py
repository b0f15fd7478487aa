"""The link to the robot through the vendor SDK: DDS set-up, RPC clients, topics, error codes.

Only the ``unitree`` backends import this module, and only inside their daemon processes: the
SDK and its DDS stack never share a process with the tree or with ROS (their DDS states would
corrupt each other, the original system's lesson).

Settings every unitree daemon takes (daemon options, else environment variables, else defaults):

- ``interface`` (``STUART_UNITREE_INTERFACE``, default ``lo``): the network interface DDS uses.
  On the robot's own computer or a laptop on its network that is the port on 192.168.123.x
  (often ``eth0``); the default keeps a mistaken start on this machine.
- ``domain`` (``STUART_UNITREE_DOMAIN``, default 0): the DDS domain id (the robot uses 0).
- ``firmware`` (``STUART_UNITREE_FIRMWARE``, default ``sport``): ``sport`` for current G1
  firmware (locomotion service "sport", Start FSM 500), ``loco`` for older firmware (service
  "loco", Start FSM 200).
- ``rpc_timeout`` (0.5 s): how long one request may wait for its answer. Short on purpose: the
  daemon loop is single-threaded and a stuck call must not starve its heartbeats.
- ``probe_timeout`` (5.0 s): how long the start-up check keeps asking each service (DDS discovery
  can take seconds).
"""

from __future__ import annotations

import json
import os
import re
import socket
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from unitree_sdk2py.core.channel import ChannelFactoryInitialize, ChannelPublisher, ChannelSubscriber
from unitree_sdk2py.rpc.client import Client

from stuart_bt.daemon import args as a
from stuart_bt.daemon.backend import DaemonError, StartupError

LINK_OPTIONS = ("interface", "domain", "firmware", "rpc_timeout", "probe_timeout")
FIRMWARES = {"sport": ("sport", 500), "loco": ("loco", 200)}  # firmware -> (loco service, Start FSM id)

# The SDK's RPC layer (rpc/internal.py) and the G1 services' own codes, in words.
VENDOR_CODES: dict[int, str] = {
    3001: "unknown RPC error",
    3102: "the request could not be sent (no such service on this interface and domain?)",
    3103: "the API is not registered in the client",
    3104: "the service did not answer in time",
    3105: "the answer belonged to another API",
    3106: "the answer could not be read",
    3107: "the lease is not valid",
    3201: "the service could not send its answer",
    3202: "the service failed internally",
    3203: "the service does not implement this API",
    3204: "the service rejected the parameters",
    3205: "another client holds the lease",
    507: "the map could not be loaded",
    7301: "locomotion is unavailable (is the robot standing in walking mode? see docs/robot.md)",
    7302: "locomotion rejected the command in the current mode",
    7303: "locomotion rejected the velocity",
    7400: "the arm is busy with another action",
    7401: "the arm holds a pose: release it (release arm, action 99) first",
    7402: "no arm action with this id",
}
TIMEOUT_CODES = (3102, 3104)


def describe(code: int) -> str:
    return VENDOR_CODES.get(code, "no description known")


@dataclass(frozen=True)
class Link:
    """Where and how to reach the robot."""

    interface: str
    domain: int
    firmware: str
    rpc_timeout: float
    probe_timeout: float

    @property
    def loco_service(self) -> str:
        return FIRMWARES[self.firmware][0]

    @property
    def start_fsm(self) -> int:
        return FIRMWARES[self.firmware][1]

    def where(self) -> str:
        return f"interface {self.interface}, DDS domain {self.domain}"


def link_from(options: dict[str, Any], family: str, own: tuple[str, ...]) -> Link:
    """The link settings in ``options`` (environment variables fill the gaps); any option that
    is neither a link setting nor one of the family's ``own`` is refused with a suggestion."""
    where = f"{family} unitree options"
    try:
        a.only_known(options, (*LINK_OPTIONS, *own), where)
        env = os.environ
        interface = a.string(options, "interface", where, default=env.get("STUART_UNITREE_INTERFACE", "lo"))
        domain_text = options.get("domain", env.get("STUART_UNITREE_DOMAIN", "0"))
        try:
            domain = int(domain_text)
        except (TypeError, ValueError):
            raise a.bad(where, f"'domain' must be a DDS domain id (0..232), got {domain_text!r}") from None
        if not 0 <= domain <= 232:
            raise a.bad(where, f"'domain' must be a DDS domain id (0..232), got {domain}")
        firmware = a.string(options, "firmware", where, default=env.get("STUART_UNITREE_FIRMWARE", "sport"),
                            choices=tuple(FIRMWARES))
        return Link(interface, domain, firmware, a.number(options, "rpc_timeout", where, default=0.5, minimum=0.01),
                    a.number(options, "probe_timeout", where, default=5.0, minimum=0.01))
    except DaemonError as e:
        raise StartupError(e.reason) from None


def startup_option(parse: Callable[[], Any]) -> Any:
    """Run an option check; a bad option stops the start-up with its one-line reason."""
    try:
        return parse()
    except DaemonError as e:
        raise StartupError(e.reason) from None


def join_dds(domain: int, interface: str) -> None:
    """``ChannelFactoryInitialize(domain, interface)`` without the trace file: the SDK's config for
    a named interface has CycloneDDS write a trace to ``/tmp/cdds.LOG`` in every process that
    joins, a file nobody reads that would outlive every run and every test. The config is the
    SDK's own, with its ``<Tracing>`` element left out. Used by the daemons and the fakes alike."""
    from unitree_sdk2py.core import channel

    channel.ChannelConfigHasInterface = re.sub(r"\s*<Tracing>.*?</Tracing>", "", channel.ChannelConfigHasInterface,
                                               flags=re.DOTALL)
    ChannelFactoryInitialize(domain, interface)


def connect(link: Link) -> None:
    """Join the DDS domain on the chosen interface (once per process; the SDK ignores repeats)."""
    if link.interface not in _interfaces():
        known = ", ".join(sorted(_interfaces()))
        raise StartupError(f"no network interface {link.interface!r} on this machine (have: {known}); "
                           "set the 'interface' option or STUART_UNITREE_INTERFACE")
    try:
        join_dds(link.domain, link.interface)
    except Exception as e:  # noqa: BLE001 - the SDK raises a bare Exception
        raise StartupError(f"cannot start DDS on {link.where()}: {e}") from None


def _interfaces() -> set[str]:
    return {name for _, name in socket.if_nameindex()}


def ready_client(client: Client, service: str, link: Link) -> Client:
    """``client`` initialised and proven: its service answered the SDK's api-version request
    within ``probe_timeout`` (asked again until then), else the daemon refuses to start, naming
    service and network."""
    client.Init()
    deadline = time.monotonic() + link.probe_timeout
    while True:  # DDS discovery takes a moment: a request sent before the service is matched is lost
        client.SetTimeout(max(0.05, min(0.5, deadline - time.monotonic())))
        code, _version = client.GetServerApiVersion()
        if code == 0 or time.monotonic() >= deadline:
            break
        time.sleep(0.05)
    if code != 0:
        raise StartupError(f"the robot's {service!r} service does not answer on {link.where()} "
                           f"(vendor code {code}: {describe(code)}); is the robot on and its service running, "
                           "and are the interface and domain right?")
    client.SetTimeout(link.rpc_timeout)
    return client


class ServiceClient(Client):
    """A JSON RPC client for a service the Python SDK has no class for (slam_operate), or for a
    known one under another name (older firmware's "loco")."""

    def __init__(self, service: str, version: str, apis: tuple[int, ...]) -> None:
        super().__init__(service, False)
        self.service = service
        self._version = version
        self._apis = apis

    def Init(self) -> None:
        self._SetApiVerson(self._version)
        for api in self._apis:
            self._RegistApi(api, 0)

    def request(self, api: int, payload: dict[str, Any]) -> tuple[int, Any]:
        code, data = self._Call(api, json.dumps(payload))
        if code == 0 and data:
            try:
                return code, json.loads(data)
            except ValueError:
                return code, data
        return code, data


def check(code: int, service: str, what: str, error: str = "backend_error", data: dict[str, Any] | None = None) -> None:
    """Raise the protocol error for a vendor answer that is not 0, with its number and meaning."""
    if code != 0:
        raise DaemonError(error, f"{service} {what} failed: vendor code {code} ({describe(code)})",
                          vendor_code=code, data=data)


def subscribe(topic: str, message_type: Any, handler: Callable[[Any], None]) -> ChannelSubscriber:
    """Call ``handler`` (on a DDS thread) with every sample of ``topic``."""
    subscriber = ChannelSubscriber(topic, message_type)
    subscriber.Init(handler, 10)
    return subscriber


def publisher(topic: str, message_type: Any) -> ChannelPublisher:
    pub = ChannelPublisher(topic, message_type)
    pub.Init()
    return pub
