/* The catalogue of diagnostic codes: the one list of every code a message may
 * carry. Messages name a code by its enum constant (internal.h builds the enum
 * from this list), so no message can show a code that is not here.
 *
 * Codes are stable: users search for them and scripts match them. Never
 * renumber; a code whose problem can no longer occur stays here and in
 * docs/graph-format.md, its meaning marked "(reserved)", so it is never given
 * to another problem. One code per distinct problem, not per call site.
 *
 * X(ENUM, "CODE", "short-name", "one-line meaning") */
#ifndef VRG_DIAG_CODES_H
#define VRG_DIAG_CODES_H

#define VRG_DIAG_CODES(X)                                                                                                                   \
    /* the file and its syntax */                                                                                                           \
    X(VRG_E_GRAPH_UNREADABLE, "VRG-E001", "graph-unreadable", "the graph file cannot be opened or read")                                    \
    X(VRG_E_GRAPH_PATH_TOO_LONG, "VRG-E002", "graph-path-too-long", "the graph file's path is longer than the runtime holds")              \
    X(VRG_E_NOT_TEXT, "VRG-E003", "not-text", "the graph file contains a NUL byte")                                                         \
    X(VRG_E_SYNTAX, "VRG-E004", "syntax-error", "a line is not a [section] header, a 'key = value' line or a comment")                      \
    X(VRG_E_KEY_OUTSIDE_SECTION, "VRG-E005", "key-outside-section", "a key comes before the first [section] header")                        \
    X(VRG_E_LINE_TOO_LONG, "VRG-E006", "line-too-long", "a line is longer than the parser reads")                                          \
    X(VRG_E_TOO_MANY, "VRG-E007", "too-many", "the graph has more keys, sections, passes or resources than the runtime holds")              \
    X(VRG_E_TOO_LONG, "VRG-E008", "too-long", "a key, value, pass name or resource name is longer than its limit")                          \
    X(VRG_E_OUT_OF_MEMORY, "VRG-E009", "out-of-memory", "host memory ran out")                                                              \
    /* sections, keys and values */                                                                                                         \
    X(VRG_E_UNKNOWN_SECTION, "VRG-E010", "unknown-section", "a section header names no known section")                                      \
    X(VRG_E_DUPLICATE_SECTION, "VRG-E011", "duplicate-section", "a section appears twice")                                                  \
    X(VRG_E_UNKNOWN_KEY, "VRG-E012", "unknown-key", "a key its section does not take")                                                      \
    X(VRG_E_DUPLICATE_KEY, "VRG-E013", "duplicate-key", "a key is given twice in one section")                                              \
    X(VRG_E_NOT_A_NUMBER, "VRG-E014", "not-a-number", "a value is not a number of the kind its key or parameter takes")                    \
    X(VRG_E_OUT_OF_RANGE, "VRG-E015", "out-of-range", "a number lies outside the range its key, parameter or call allows")                 \
    X(VRG_E_UNKNOWN_FORMAT, "VRG-E016", "unknown-format", "a [resource] format names no format the runtime knows")                          \
    X(VRG_E_SIZE_KEYS, "VRG-E017", "size-keys", "a [resource] gives only one of width and height, or a scale and a size")                  \
    X(VRG_E_INVALID_NAME, "VRG-E018", "invalid-name", "a pass or resource name uses characters names may not")                              \
    X(VRG_E_BAD_PLUGIN_PATH, "VRG-E019", "bad-plugin-path", "a plugin_path entry is empty, too long or not a folder")                       \
    /* the graph's structure */                                                                                                             \
    X(VRG_E_NO_GRAPH_SECTION, "VRG-E020", "no-graph-section", "the file has no [graph] section")                                            \
    X(VRG_E_NO_OUTPUT, "VRG-E021", "no-output", "[graph] names no output resource")                                                         \
    X(VRG_E_NO_SIZE, "VRG-E022", "no-size", "the graph has no width and height")                                                            \
    X(VRG_E_OUTPUT_NEVER_WRITTEN, "VRG-E023", "output-never-written", "the output resource is written by no pass")                          \
    X(VRG_E_OUTPUT_NOT_IMAGE, "VRG-E024", "output-not-image", "the output resource is a buffer")                                            \
    X(VRG_E_DUPLICATE_PASS, "VRG-E025", "duplicate-pass", "two passes have one name")                                                       \
    X(VRG_E_NO_PLUGIN, "VRG-E026", "no-plugin", "a [pass] or [scene] section has no plugin key")                                            \
    X(VRG_E_PLUGIN_KIND, "VRG-E027", "plugin-kind", "a scene plugin in a [pass] section, or a pass plugin in [scene]")                      \
    X(VRG_E_UNKNOWN_SLOT, "VRG-E028", "unknown-slot", "in.SLOT or out.SLOT names no slot of the plugin")                                   \
    X(VRG_E_SLOT_DIRECTION, "VRG-E029", "slot-direction", "an input slot is connected as out., or an output as in.")                       \
    X(VRG_E_SLOT_CONNECTED_TWICE, "VRG-E030", "slot-connected-twice", "a slot is connected twice in one pass")                              \
    X(VRG_E_BAD_PREV, "VRG-E031", "bad-prev", "'@prev' on an output, or another '@' suffix")                                                \
    X(VRG_E_PREV_OF_PERSISTENT, "VRG-E032", "prev-of-persistent", "NAME@prev reads a persistent resource, which has no last frame's copy")  \
    X(VRG_E_TWO_WRITERS, "VRG-E033", "two-writers", "two passes write one resource")                                                        \
    X(VRG_E_INPUT_NOT_CONNECTED, "VRG-E034", "input-not-connected", "a required input of a pass is not connected")                          \
    X(VRG_E_NEVER_WRITTEN, "VRG-E035", "never-written", "a pass reads a resource that no pass writes")                                      \
    X(VRG_E_KIND_MISMATCH, "VRG-E036", "kind-mismatch", "a slot takes another kind (image, buffer, acceleration structure) than it gets")   \
    X(VRG_E_KEY_WRONG_KIND, "VRG-E037", "key-wrong-kind", "a [resource] key does not apply to the kind of resource it is, or output_scale to a pass with no relative-size image output")                 \
    X(VRG_E_FORMAT_MISMATCH, "VRG-E038", "format-mismatch", "a resource's format or texel format is not the one a slot needs")             \
    X(VRG_E_BUFFER_SIZE, "VRG-E039", "buffer-size", "a buffer has size 0 or is not a whole number of its texels")                           \
    X(VRG_E_SIZE_MISMATCH, "VRG-E040", "size-mismatch", "a resource's size is not the one a slot or pass needs")                           \
    X(VRG_E_LAYOUT_CONFLICT, "VRG-E041", "layout-conflict", "one resource is bound to two slots of a pass that need different layouts")    \
    X(VRG_E_CYCLE, "VRG-E042", "cycle", "passes read each other's outputs in a cycle")                                                      \
    X(VRG_E_BAD_OVERRIDE, "VRG-E043", "bad-override", "a --set override is not PASS.PARAM=VALUE")                                           \
    X(VRG_E_UNKNOWN_PARAMETER, "VRG-E044", "unknown-parameter", "an override names no pass, or no parameter of its pass")                  \
    X(VRG_E_PARAM_NOT_SETTABLE, "VRG-E045", "param-not-settable", "a string parameter, or one read only at creation, is set while the graph runs")                       \
    X(VRG_E_UNKNOWN_RESOURCE, "VRG-E046", "unknown-resource", "a read-back, dump or view names no resource of the graph")                   \
    X(VRG_E_NOT_A_CHOICE, "VRG-E047", "not-a-choice", "a string parameter's value is not one of the choices its plugin takes")              \
    /* plugins */                                                                                                                           \
    X(VRG_E_UNKNOWN_PLUGIN, "VRG-E050", "unknown-plugin", "no plugin of that name is on the search path")                                  \
    X(VRG_E_PLUGIN_LOAD_FAILED, "VRG-E051", "plugin-load-failed", "the plugin file is found but cannot be loaded")                         \
    X(VRG_E_PLUGIN_NO_ENTRY, "VRG-E052", "plugin-no-entry", "the plugin exports no descriptor, or its descriptor function returns NULL")   \
    X(VRG_E_PLUGIN_ABI, "VRG-E053", "plugin-abi", "the plugin was built against another ABI version or descriptor size")                  \
    X(VRG_E_PLUGIN_BAD_DESC, "VRG-E054", "plugin-bad-desc", "the plugin's descriptor is malformed (callbacks, slots, parameters)")         \
    X(VRG_E_TOO_MANY_PLUGINS, "VRG-E055", "too-many-plugins", "more plugin versions are loaded than a process holds")                      \
    X(VRG_E_PLUGIN_NAME_TOO_LONG, "VRG-E056", "plugin-name-too-long", "a plugin file's name is too long for a graph to name it")          \
    X(VRG_E_NOT_A_LOADED_PLUGIN, "VRG-E057", "not-a-loaded-plugin", "a reload names a file that is no loaded plugin")                     \
    X(VRG_E_PASS_FAILED, "VRG-E058", "pass-failed", "a pass's plugin reported an error (vrg_pass_error)")                                   \
    X(VRG_E_CALLBACK_FAILED, "VRG-E059", "callback-failed", "a plugin's check, create, resize, save_state or restore_state failed")        \
    X(VRG_E_SHADER_FAILED, "VRG-E060", "shader-failed", "a pass's shader is not found, does not compile or makes no pipeline")             \
    X(VRG_E_BAD_DISPATCH, "VRG-E061", "bad-dispatch", "a pass's dispatch cannot be recorded (bindings, push constants, domain)")            \
    X(VRG_E_PASS_API_MISUSE, "VRG-E062", "pass-api-misuse", "a plugin called the pass API at the wrong time or with wrong names")           \
    X(VRG_E_SHADER_SOURCE, "VRG-E063", "shader-source", "a shader or a file it #includes has a GLSL error, a bad #include, cannot be read or is empty") \
    X(VRG_E_SHADER_BINDING_UNBOUND, "VRG-E064", "shader-binding-unbound", "a shader declares a binding its dispatch does not bind (no slot or resource there, or a set other than 0)") \
    X(VRG_E_SHADER_BINDING_TYPE, "VRG-E065", "shader-binding-type", "a shader's binding has another descriptor type than the bound slot's access gives") \
    X(VRG_E_SHADER_IMAGE_FORMAT, "VRG-E066", "shader-image-format", "a shader's storage image format qualifier is not the bound image's format") \
    X(VRG_E_SHADER_PUSH_SIZE, "VRG-E067", "shader-push-size", "a shader's push-constant block is not the size of the push constants its dispatch gives") \
    X(VRG_E_SHADER_ACCESS, "VRG-E068", "shader-access", "a shader declares a storage binding readonly that its dispatch binds for writing, or writeonly for reading") \
    /* the device and the running graph */                                                                                                  \
    X(VRG_E_DEVICE_UNSUPPORTED, "VRG-E070", "device-unsupported", "the device lacks an extension, format or size the graph needs")         \
    X(VRG_E_VULKAN_FAILED, "VRG-E071", "vulkan-failed", "creating a Vulkan object, device memory or a submission failed")                  \
    X(VRG_E_GPU_TIMEOUT, "VRG-E072", "gpu-timeout", "a frame ran on the GPU past its limit, or was interrupted")                           \
    X(VRG_E_GPU_BUSY, "VRG-E073", "gpu-busy", "the GPU is still busy with a frame that timed out or was interrupted")                      \
    X(VRG_E_DEVICE_LOST, "VRG-E074", "device-lost", "waiting for the GPU failed")                                                          \
    X(VRG_E_NO_DEVICE, "VRG-E075", "no-device", "the graph was loaded without a device (or not from a file) and cannot do this")            \
    X(VRG_E_NOT_READ_BACK, "VRG-E076", "not-read-back", "a resource is read that is not read back or kept, or before a frame ran")         \
    X(VRG_E_WRONG_READ, "VRG-E077", "wrong-read", "an image is read as a buffer, or a buffer as an image")                                 \
    X(VRG_E_WATCH_FAILED, "VRG-E078", "watch-failed", "hot reload cannot watch the graph's files")                                        \
    X(VRG_E_PIXEL_OUTSIDE, "VRG-E079", "pixel-outside", "a pixel is read that lies outside the graph's size")                             \
    X(VRG_E_SHADER_INTERFACE, "VRG-E080", "shader-interface", "a shader-only pass's shader does not declare a valid interface (binding names, @param and @optional annotations)") \
    X(VRG_E_NOT_FINITE, "VRG-E081", "not-finite", "a pass wrote NaN or infinity into a float image (check_finite)")                     \
    X(VRG_E_SHADER_PUSH_MEMBER, "VRG-E082", "shader-push-member", "a push-constant member packed by name has no value (no parameter or vrg_push_* of its name), another type, or a value names no member") \
    X(VRG_E_SHADER_BINDING_NAME, "VRG-E083", "shader-binding-name", "a binding named after a slot or internal resource (in_X, out_X, frame) is bound to another resource (two bindings swapped), or names neither") \
    /* warnings */                                                                                                                          \
    X(VRG_W_UNUSED_RESOURCE, "VRG-W001", "unused-resource", "a [resource] section configures a resource no pass uses")                    \
    X(VRG_W_PLUGIN_SHADOWED, "VRG-W002", "plugin-shadowed", "a plugin of the same name earlier on the search path is used instead")     \
    X(VRG_W_SHADER_WARNING, "VRG-W003", "shader-warning", "the GLSL compiler warns about a shader or a file it #includes") \
    X(VRG_W_UNUSED_BINDING, "VRG-W004", "unused-binding", "a dispatch binds a slot or resource at a binding its shader does not declare") \
    X(VRG_W_ACCESS_QUALIFIER, "VRG-W005", "access-qualifier", "a storage binding bound for reading (writing) only is not declared readonly (writeonly)") \
    X(VRG_W_PASS_WARNING, "VRG-W006", "pass-warning", "a pass's plugin warns about its input (vrg_pass_warn_at) and goes on") \
    X(VRG_W_PLUGIN_WRITABLE, "VRG-W007", "plugin-writable", "a plugin's file, or its folder, is writable by every user") \
    X(VRG_W_PASS_CULLED, "VRG-W008", "pass-culled", "a pass is culled: nothing it writes reaches the output, a history resource or a read-back")

#endif
