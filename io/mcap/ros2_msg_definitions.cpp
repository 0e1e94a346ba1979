#include "io/mcap/ros2_msg_definitions.hpp"

#include <algorithm>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "geometry/error.hpp"

namespace owsim::ros2 {
namespace {

// One .msg file: its name as another .msg refers to it ("pkg/Type"), the types it refers to
// (sorted, as rosbag2 collects them), and its text.
struct MsgFile {
  std::string_view name;
  std::vector<std::string_view> dependencies;
  std::string_view text;
};

// The files of ROS 2 Jazzy Jalisco, byte for byte (ros2/common_interfaces, ros2/rcl_interfaces
// and ros2/geometry2 at their jazzy branches; Apache License 2.0).
const std::vector<MsgFile>& msg_files() {
  static const std::vector<MsgFile> files = {
      {"builtin_interfaces/Duration",
       {},
       R"msg(# Duration defines a period between two time points.
# Messages of this datatype are of ROS Time following this design:
# https://design.ros2.org/articles/clock_and_time.html

# Seconds component, range is valid over any possible int32 value.
int32 sec

# Nanoseconds component in the range of [0, 1e9).
uint32 nanosec
)msg"},
      {"builtin_interfaces/Time",
       {},
       R"msg(# This message communicates ROS Time defined here:
# https://design.ros2.org/articles/clock_and_time.html

# The seconds component, valid over all int32 values.
int32 sec

# The nanoseconds component, valid in the range [0, 1e9).
uint32 nanosec
)msg"},
      {"geometry_msgs/Point",
       {},
       R"msg(# This contains the position of a point in free space
float64 x
float64 y
float64 z
)msg"},
      {"geometry_msgs/Pose",
       {"geometry_msgs/Point", "geometry_msgs/Quaternion"},
       R"msg(# A representation of pose in free space, composed of position and orientation.

Point position
Quaternion orientation
)msg"},
      {"geometry_msgs/Quaternion",
       {},
       R"msg(# This represents an orientation in free space in quaternion form.

float64 x 0
float64 y 0
float64 z 0
float64 w 1
)msg"},
      {"geometry_msgs/Transform",
       {"geometry_msgs/Quaternion", "geometry_msgs/Vector3"},
       R"msg(# This represents the transform between two coordinate frames in free space.

Vector3 translation
Quaternion rotation
)msg"},
      {"geometry_msgs/TransformStamped",
       {"geometry_msgs/Transform", "std_msgs/Header"},
       R"msg(# This expresses a transform from coordinate frame header.frame_id
# to the coordinate frame child_frame_id at the time of header.stamp
#
# This message is mostly used by the
# <a href="https://docs.ros.org/en/rolling/p/tf2/">tf2</a> package.
# See its documentation for more information.
#
# The child_frame_id is necessary in addition to the frame_id
# in the Header to communicate the full reference for the transform
# in a self contained message.

# The frame id in the header is used as the reference frame of this transform.
std_msgs/Header header

# The frame id of the child frame to which this transform points.
string child_frame_id

# Translation and rotation in 3-dimensions of child_frame_id from header.frame_id.
Transform transform
)msg"},
      {"geometry_msgs/Vector3",
       {},
       R"msg(# This represents a vector in free space.

# This is semantically different than a point.
# A vector is always anchored at the origin.
# When a transform is applied to a vector, only the rotational component is applied.

float64 x
float64 y
float64 z
)msg"},
      {"sensor_msgs/CompressedImage",
       {"std_msgs/Header"},
       R"msg(# This message contains a compressed image.

std_msgs/Header header # Header timestamp should be acquisition time of image
                             # Header frame_id should be optical frame of camera
                             # origin of frame should be optical center of cameara
                             # +x should point to the right in the image
                             # +y should point down in the image
                             # +z should point into to plane of the image

string format                # Specifies the format of the data
                             # Acceptable values differ by the image transport used:
                             # - compressed_image_transport:
                             #     ORIG_PIXFMT; CODEC compressed [COMPRESSED_PIXFMT]
                             #   where:
                             #   - ORIG_PIXFMT is pixel format of the raw image, i.e.
                             #     the content of sensor_msgs/Image/encoding with
                             #     values from include/sensor_msgs/image_encodings.h
                             #   - CODEC is one of [jpeg, png, tiff]
                             #   - COMPRESSED_PIXFMT is only appended for color images
                             #     and is the pixel format used by the compression
                             #     algorithm. Valid values for jpeg encoding are:
                             #     [bgr8, rgb8]. Valid values for png encoding are:
                             #     [bgr8, rgb8, bgr16, rgb16].
                             #   If the field is empty or does not correspond to the
                             #   above pattern, the image is treated as bgr8 or mono8
                             #   jpeg image (depending on the number of channels).
                             # - compressed_depth_image_transport:
                             #     ORIG_PIXFMT; compressedDepth CODEC
                             #   where:
                             #   - ORIG_PIXFMT is pixel format of the raw image, i.e.
                             #     the content of sensor_msgs/Image/encoding with
                             #     values from include/sensor_msgs/image_encodings.h
                             #     It is usually one of [16UC1, 32FC1].
                             #   - CODEC is one of [png, rvl]
                             #   If the field is empty or does not correspond to the
                             #   above pattern, the image is treated as png image.
                             # - Other image transports can store whatever values they
                             #   need for successful decoding of the image. Refer to
                             #   documentation of the other transports for details.

uint8[] data                 # Compressed image buffer
)msg"},
      {"sensor_msgs/NavSatFix",
       {"sensor_msgs/NavSatStatus", "std_msgs/Header"},
       R"msg(# Navigation Satellite fix for any Global Navigation Satellite System
#
# Specified using the WGS 84 reference ellipsoid

# header.stamp specifies the ROS time for this measurement (the
#        corresponding satellite time may be reported using the
#        sensor_msgs/TimeReference message).
#
# header.frame_id is the frame of reference reported by the satellite
#        receiver, usually the location of the antenna.  This is a
#        Euclidean frame relative to the vehicle, not a reference
#        ellipsoid.
std_msgs/Header header

# Satellite fix status information.
NavSatStatus status

# Latitude [degrees]. Positive is north of equator; negative is south.
float64 latitude

# Longitude [degrees]. Positive is east of prime meridian; negative is west.
float64 longitude

# Altitude [m]. Positive is above the WGS 84 ellipsoid
# (quiet NaN if no altitude is available).
float64 altitude

# Position covariance [m^2] defined relative to a tangential plane
# through the reported position. The components are East, North, and
# Up (ENU), in row-major order.
#
# Beware: this coordinate system exhibits singularities at the poles.
float64[9] position_covariance

# If the covariance of the fix is known, fill it in completely. If the
# GPS receiver provides the variance of each measurement, put them
# along the diagonal. If only Dilution of Precision is available,
# estimate an approximate covariance from that.

uint8 COVARIANCE_TYPE_UNKNOWN = 0
uint8 COVARIANCE_TYPE_APPROXIMATED = 1
uint8 COVARIANCE_TYPE_DIAGONAL_KNOWN = 2
uint8 COVARIANCE_TYPE_KNOWN = 3

uint8 position_covariance_type
)msg"},
      {"sensor_msgs/NavSatStatus",
       {},
       R"msg(# Navigation Satellite fix status for any Global Navigation Satellite System.
#
# Whether to output an augmented fix is determined by both the fix
# type and the last time differential corrections were received.  A
# fix is valid when status >= STATUS_FIX.

int8 STATUS_UNKNOWN = -2        # status is not yet set
int8 STATUS_NO_FIX =  -1        # unable to fix position
int8 STATUS_FIX =      0        # unaugmented fix
int8 STATUS_SBAS_FIX = 1        # with satellite-based augmentation
int8 STATUS_GBAS_FIX = 2        # with ground-based augmentation

int8 status -2 # STATUS_UNKNOWN

# Bits defining which Global Navigation Satellite System signals were
# used by the receiver.

uint16 SERVICE_UNKNOWN = 0  # Remember service is a bitfield, so checking (service & SERVICE_UNKNOWN) will not work. Use == instead.
uint16 SERVICE_GPS =     1
uint16 SERVICE_GLONASS = 2
uint16 SERVICE_COMPASS = 4      # includes BeiDou.
uint16 SERVICE_GALILEO = 8

uint16 service
)msg"},
      {"sensor_msgs/PointCloud2",
       {"sensor_msgs/PointField", "std_msgs/Header"},
       R"msg(# This message holds a collection of N-dimensional points, which may
# contain additional information such as normals, intensity, etc. The
# point data is stored as a binary blob, its layout described by the
# contents of the "fields" array.
#
# The point cloud data may be organized 2d (image-like) or 1d (unordered).
# Point clouds organized as 2d images may be produced by camera depth sensors
# such as stereo or time-of-flight.

# Time of sensor data acquisition, and the coordinate frame ID (for 3d points).
std_msgs/Header header

# 2D structure of the point cloud. If the cloud is unordered, height is
# 1 and width is the length of the point cloud.
uint32 height
uint32 width

# Describes the channels and their layout in the binary data blob.
PointField[] fields

bool    is_bigendian # Is this data bigendian?
uint32  point_step   # Length of a point in bytes
uint32  row_step     # Length of a row in bytes
uint8[] data         # Actual point data, size is (row_step*height)

bool is_dense        # True if there are no invalid points
)msg"},
      {"sensor_msgs/PointField",
       {},
       R"msg(# This message holds the description of one point entry in the
# PointCloud2 message format.
uint8 INT8    = 1
uint8 UINT8   = 2
uint8 INT16   = 3
uint8 UINT16  = 4
uint8 INT32   = 5
uint8 UINT32  = 6
uint8 FLOAT32 = 7
uint8 FLOAT64 = 8

# Common PointField names are x, y, z, intensity, rgb, rgba
string name      # Name of field
uint32 offset    # Offset from start of point struct
uint8  datatype  # Datatype enumeration, see above
uint32 count     # How many elements in the field
)msg"},
      {"std_msgs/ColorRGBA",
       {},
       R"msg(float32 r
float32 g
float32 b
float32 a
)msg"},
      {"std_msgs/Header",
       {"builtin_interfaces/Time"},
       R"msg(# Standard metadata for higher-level stamped data types.
# This is generally used to communicate timestamped data
# in a particular coordinate frame.

# Two-integer timestamp that is expressed as seconds and nanoseconds.
builtin_interfaces/Time stamp

# Transform frame with which this data is associated.
string frame_id
)msg"},
      {"tf2_msgs/TFMessage",
       {"geometry_msgs/TransformStamped"},
       R"msg(geometry_msgs/TransformStamped[] transforms
)msg"},
      {"visualization_msgs/Marker",
       {"builtin_interfaces/Duration", "geometry_msgs/Point", "geometry_msgs/Pose",
        "geometry_msgs/Vector3", "sensor_msgs/CompressedImage", "std_msgs/ColorRGBA",
        "std_msgs/Header", "visualization_msgs/MeshFile", "visualization_msgs/UVCoordinate"},
       R"msg(# See:
#  - http://www.ros.org/wiki/rviz/DisplayTypes/Marker
#  - http://www.ros.org/wiki/rviz/Tutorials/Markers%3A%20Basic%20Shapes
#
# for more information on using this message with rviz.

int32 ARROW=0
int32 CUBE=1
int32 SPHERE=2
int32 CYLINDER=3
int32 LINE_STRIP=4
int32 LINE_LIST=5
int32 CUBE_LIST=6
int32 SPHERE_LIST=7
int32 POINTS=8
int32 TEXT_VIEW_FACING=9
int32 MESH_RESOURCE=10
int32 TRIANGLE_LIST=11
int32 ARROW_STRIP=12

int32 ADD=0
int32 MODIFY=0
int32 DELETE=2
int32 DELETEALL=3

# Header for timestamp and frame id.
std_msgs/Header header
# Namespace in which to place the object.
# Used in conjunction with id to create a unique name for the object.
string ns
# Object ID used in conjunction with the namespace for manipulating and deleting the object later.
int32 id
# Type of object.
int32 type
# Action to take; one of:
#  - 0 add/modify an object
#  - 1 (deprecated)
#  - 2 deletes an object (with the given ns and id)
#  - 3 deletes all objects (or those with the given ns if any)
int32 action
# Pose of the object with respect the frame_id specified in the header.
geometry_msgs/Pose pose
# Scale of the object; 1,1,1 means default (usually 1 meter square).
geometry_msgs/Vector3 scale
# Color of the object; in the range: [0.0-1.0]
std_msgs/ColorRGBA color
# How long the object should last before being automatically deleted.
# 0 indicates forever.
builtin_interfaces/Duration lifetime
# If this marker should be frame-locked, i.e. retransformed into its frame every timestep.
bool frame_locked

# Only used if the type specified has some use for them (eg. POINTS, LINE_STRIP, ARROW_STRIP, etc.)
geometry_msgs/Point[] points
# Only used if the type specified has some use for them (eg. POINTS, LINE_STRIP, etc.)
# The number of colors provided must either be 0 or equal to the number of points provided.
# NOTE: alpha is not yet used
std_msgs/ColorRGBA[] colors

# Texture resource is a special URI that can either reference a texture file in
# a format acceptable to (resource retriever)[https://docs.ros.org/en/rolling/p/resource_retriever/]
# or an embedded texture via a string matching the format:
#   "embedded://texture_name"
string texture_resource
# An image to be loaded into the rendering engine as the texture for this marker.
# This will be used iff texture_resource is set to embedded.
sensor_msgs/CompressedImage texture
# Location of each vertex within the texture; in the range: [0.0-1.0]
UVCoordinate[] uv_coordinates

# Only used for text markers
string text

# Only used for MESH_RESOURCE markers.
# Similar to texture_resource, mesh_resource uses resource retriever to load a mesh.
# Optionally, a mesh file can be sent in-message via the mesh_file field. If doing so,
# use the following format for mesh_resource:
#   "embedded://mesh_name"
string mesh_resource
MeshFile mesh_file
bool mesh_use_embedded_materials
)msg"},
      {"visualization_msgs/MarkerArray",
       {"visualization_msgs/Marker"},
       R"msg(Marker[] markers
)msg"},
      {"visualization_msgs/MeshFile",
       {},
       R"msg(# Used to send raw mesh files.

# The filename is used for both debug purposes and to provide a file extension
# for whatever parser is used.
string filename

# This stores the raw text of the mesh file.
uint8[] data
)msg"},
      {"visualization_msgs/UVCoordinate",
       {},
       R"msg(# Location of the pixel as a ratio of the width of a 2D texture.
# Values should be in range: [0.0-1.0].
float32 u
float32 v
)msg"},
  };
  return files;
}

const MsgFile& msg_file(std::string_view name) {
  for (const MsgFile& file : msg_files()) {
    if (file.name == name) return file;
  }
  throw Error("no ROS 2 message definition for " + std::string(name));
}

}  // namespace

std::string ros2msg_schema(std::string_view type) {
  // "pkg/msg/Type" is the file "pkg/Type".
  const std::size_t first = type.find('/');
  const std::size_t last = type.rfind('/');
  if (first == std::string_view::npos || type.substr(first, last - first + 1) != "/msg/") {
    throw Error("not a ROS 2 message type name (pkg/msg/Type): " + std::string(type));
  }
  const std::string root = std::string(type.substr(0, first)) + std::string(type.substr(last));
  std::set<std::string_view> seen;
  const std::function<std::string(const MsgFile&)> append = [&](const MsgFile& file) {
    std::string text(file.text);
    for (const std::string_view dependency : file.dependencies) {
      if (!seen.insert(dependency).second) continue;
      text += '\n';
      text.append(80, '=');
      text += "\nMSG: ";
      text += dependency;
      text += '\n';
      text += append(msg_file(dependency));
    }
    return text;
  };
  return append(msg_file(root));
}

}  // namespace owsim::ros2
