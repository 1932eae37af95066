/*
 * gaitopt reference walking controller: C interface (C99, C standard library only).
 *
 * Built as the shared library libgaitopt_walker.so. A controller is loaded from the file
 * `gaitopt export --format json` writes and walks that gait's cyclic step for as long as
 * it is called.
 *
 * Conventions (docs/conventions.md and docs/formats/controller-export.md):
 * - world frame: x forward (the walking direction), z up, the robot in the sagittal x-z
 *   plane seen from its left; SI units; every angle in rad, counter-clockwise positive
 *   (from +x toward +z);
 * - physical joints j = 0..3 in the order knee_left, hip_left, hip_right, knee_right
 *   (left = leg 1 of the robot file); every per-joint array uses this order;
 * - phi[j] is the joint-side motor angle φ_J of the export (the joint value of the
 *   `gaitopt export-model` MJCF/URDF): straight knee −π, femur hanging straight down
 *   under an upright trunk: hip π.
 */
#ifndef GAITOPT_CONTROL_WALKER_H
#define GAITOPT_CONTROL_WALKER_H

#ifdef __cplusplus
extern "C" {
#endif

/* Incremented when a name, a type, a layout or a meaning below changes. */
#define GAITOPT_WALKER_API_VERSION 1

/* Opaque controller: created by gaitopt_walker_load, released by gaitopt_walker_free. */
typedef struct gaitopt_walker gaitopt_walker;

/* The measured state of the robot at time t.
 * t                time [s]; non-decreasing over the calls of one controller
 * x_hip, z_hip     the hip joint in the world frame [m]
 * pitch            the trunk from the vertical, the export's trunk_angle = θ3 − π/2 [rad]
 *                  (> 0 leaning backward)
 * phi[4]           joint-side motor angles φ_J [rad] (knee_left, hip_left, hip_right,
 *                  knee_right)
 * xd_hip, zd_hip, pitchd, phid[4]   the time derivatives of the above [m/s, rad/s]
 * contact[2]       left, right foot on the ground: 1 when its normal force is above 1 N
 *                  (or its contact switch is closed), else 0 */
typedef struct {
    double t;
    double x_hip, z_hip, pitch, phi[4];
    double xd_hip, zd_hip, pitchd, phid[4];
    int contact[2];
} gaitopt_walker_state;

/* The cyclic gait the controller walks.
 * speed            mean forward speed [m/s]
 * step_length      stance foot to stance foot [m]
 * t_ss, t_ds       single- and double-support durations [s] (t_ds 0 for gaits without DS)
 * torque_max[4]    the torque envelope's plateau per physical joint [N·m]
 * robot_file       the robot file the export names (NUL-terminated, truncated to fit) */
typedef struct {
    double speed, step_length, t_ss, t_ds;
    double torque_max[4];
    char robot_file[1024];
} gaitopt_walker_info;

/* Loads a controller from export_path, a file written by `gaitopt export --format json`
 * (nothing else is read).
 * options: NULL for the defaults, or a YAML mapping overriding any of these keys:
 *   gain_scale     default 1: scales the PD gains of the outputs in the phase domain
 *                  (Kp = gain_scale bandwidth², Kd = gain_scale 2 bandwidth), > 0
 *   bandwidth      default 40: the outputs' bandwidth ω [rad/s], > 0
 *   ds_control     default time_optimal: double-support control of α, time_optimal
 *                  (the cyclic curve at the bounds of the LPs (4.14)) or cubic
 *   torque_limits  default true: project the inputs on the torque envelope and the
 *                  contact constraints
 *   lean_gain      default 0.1: single-support speed regulation, trunk lean [rad] per
 *                  relative error of the last step's speed (back when too fast), >= 0
 *   lean_integral_gain  default 0.05: trunk lean [rad] added per relative step speed
 *                  error, summed over the steps, >= 0 (with a double support the lean acts
 *                  once the double support's rate correction is at its bound)
 *   max_lean       default 0.6: bound of the trunk lean [rad], > 0
 *   slope_compensation  default 1: scale of the trunk lean that compensates a downhill slope
 *                  measured between the feet at each touchdown, >= 0 (0: off)
 *   slope_deadband default 0.005: a measured slope within +- this [rad] is level, >= 0
 *   apex_energy_fraction  default 0.5: the single support must pass over the stance foot
 *                  with at least this fraction of the gait's own squared angular momentum
 *                  there (predicted from the gait's zero dynamics): the double support does
 *                  not end before, its speed correction never targets less, and the trunk
 *                  lean back of the speed regulation stays within what is left, >= 0 (0: the
 *                  single support only has to pass)
 * An unknown key, a value of the wrong type or out of range is an error.
 * Returns NULL on failure and then, unless error is NULL, writes a NUL-terminated message
 * naming the file (or the options key) and the problem into error, truncated to
 * error_size bytes. */
gaitopt_walker* gaitopt_walker_load(const char* export_path, const char* options, char* error,
                                    int error_size);

/* The state the walk starts from: the first sample of a single support, the stance foot at
 * rest on the ground at x = 0 (contact 1 for the stance foot, 0 for the swing foot), t = 0.
 * Returns 0, or −1 when an argument is NULL. */
int gaitopt_walker_initial_state(const gaitopt_walker* w, gaitopt_walker_state* out);

/* The cyclic gait's figures (see gaitopt_walker_info). Returns 0, or −1 when an argument is
 * NULL. */
int gaitopt_walker_get_info(const gaitopt_walker* w, gaitopt_walker_info* out);

/* The cyclic gait's mean forward speed [m/s] (0 when w is NULL). */
double gaitopt_walker_speed(const gaitopt_walker* w);

/* Writes into tau the joint-side motor torques Γ* [N·m] (what the motors apply; the
 * joint's friction and rotor inertia belong to the plant), physical joint order, within
 * the torque envelope at each joint's current speed.
 * Valid for any call rate of at least 500 Hz, the torques being held until the next call;
 * the controller walks the cyclic gait for as long as it is called. The states passed over
 * the calls must be consistent (one robot, t non-decreasing).
 * Returns 0 normally, 1 when it judges the robot fallen, −1 when an argument is NULL. */
int gaitopt_walker_torques(gaitopt_walker* w, const gaitopt_walker_state* s, double tau[4]);

/* Releases the controller (NULL is allowed). */
void gaitopt_walker_free(gaitopt_walker* w);

#ifdef __cplusplus
}
#endif

#endif /* GAITOPT_CONTROL_WALKER_H */
