"""The tests' own DDS types for the ROS 2 messages the bridge speaks, written
here from the ROS 2 definitions (ros2/common_interfaces, ros2/rmw_dds_common;
the request header of rmw_cyclonedds' services), named as rosidl names them
for DDS, and shared by the Cyclone DDS tests. Deliberately not the bridge's
(bridge/schema.py): an independent reader of what it writes."""

# no "from __future__ import annotations": cyclonedds resolves the IDL
# classes' annotations as objects

from dataclasses import dataclass

from cyclonedds.idl import IdlStruct
from cyclonedds.idl import types as t


@dataclass
class Time_(IdlStruct, typename="builtin_interfaces::msg::dds_::Time_"):
    sec: t.int32
    nanosec: t.uint32


@dataclass
class Header_(IdlStruct, typename="std_msgs::msg::dds_::Header_"):
    stamp: Time_
    frame_id: str


@dataclass
class Vector3_(IdlStruct, typename="geometry_msgs::msg::dds_::Vector3_"):
    x: t.float64
    y: t.float64
    z: t.float64


@dataclass
class Wrench_(IdlStruct, typename="geometry_msgs::msg::dds_::Wrench_"):
    force: Vector3_
    torque: Vector3_


@dataclass
class WrenchStamped_(IdlStruct, typename="geometry_msgs::msg::dds_::WrenchStamped_"):
    header: Header_
    wrench: Wrench_


@dataclass
class KeyValue_(IdlStruct, typename="diagnostic_msgs::msg::dds_::KeyValue_"):
    key: str
    value: str


@dataclass
class DiagnosticStatus_(IdlStruct, typename="diagnostic_msgs::msg::dds_::DiagnosticStatus_"):
    level: t.uint8
    name: str
    message: str
    hardware_id: str
    values: t.sequence[KeyValue_]


@dataclass
class DiagnosticArray_(IdlStruct, typename="diagnostic_msgs::msg::dds_::DiagnosticArray_"):
    header: Header_
    status: t.sequence[DiagnosticStatus_]


@dataclass
class Empty_(IdlStruct, typename="std_msgs::msg::dds_::Empty_"):
    structure_needs_at_least_one_member: t.uint8


@dataclass
class Gid_(IdlStruct, typename="rmw_dds_common::msg::dds_::Gid_"):
    data: t.array[t.uint8, 16]


@dataclass
class NodeEntitiesInfo_(IdlStruct, typename="rmw_dds_common::msg::dds_::NodeEntitiesInfo_"):
    node_namespace: t.bounded_str[256]
    node_name: t.bounded_str[256]
    reader_gid_seq: t.sequence[Gid_]
    writer_gid_seq: t.sequence[Gid_]


@dataclass
class ParticipantEntitiesInfo_(IdlStruct,
                               typename="rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_"):
    gid: Gid_
    node_entities_info_seq: t.sequence[NodeEntitiesInfo_]


@dataclass
class Vector3Stamped_(IdlStruct, typename="geometry_msgs::msg::dds_::Vector3Stamped_"):
    header: Header_
    vector: Vector3_


@dataclass
class TriggerRequest_(IdlStruct, typename="std_srvs::srv::dds_::Trigger_Request_"):
    client_guid: t.uint64  # rmw_cyclonedds' request header ...
    sequence_number: t.int64  # ... then the request
    structure_needs_at_least_one_member: t.uint8


@dataclass
class TriggerResponse_(IdlStruct, typename="std_srvs::srv::dds_::Trigger_Response_"):
    client_guid: t.uint64
    sequence_number: t.int64
    success: bool
    message: str


# Humble's Gid: 24 bytes
@dataclass
class Gid24_(IdlStruct, typename="rmw_dds_common::msg::dds_::Gid_"):
    data: t.array[t.uint8, 24]


@dataclass
class NodeEntitiesInfo24_(IdlStruct, typename="rmw_dds_common::msg::dds_::NodeEntitiesInfo_"):
    node_namespace: t.bounded_str[256]
    node_name: t.bounded_str[256]
    reader_gid_seq: t.sequence[Gid24_]
    writer_gid_seq: t.sequence[Gid24_]


@dataclass
class ParticipantEntitiesInfo24_(
        IdlStruct, typename="rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_"):
    gid: Gid24_
    node_entities_info_seq: t.sequence[NodeEntitiesInfo24_]
