/*
 * The venv's repair of Fast DDS 2.14.5 (the pinned ros-jazzy wheels): a new participant starts
 * receiving before it announces itself.
 *
 * RTPSParticipantImpl::enable() enables the builtin protocols first, which sends the participant's
 * first discovery announcement (SPDP) to every well-known port, and only then registers the
 * receivers of its sockets. Until a socket's receiver is registered, its reading thread drops
 * what arrives. The running participants answer the announcement within a millisecond, so about
 * 4 answers in 10 were dropped, and the newcomer learnt of those participants only from their
 * next periodic announcement (0.5 s apart in config/fastdds.xml): a `ros2` verb or a student's
 * node saw part of the graph for up to half a second. Upstream has the same order on master; an
 * open pull request (eProsima/Fast-DDS#6204) swaps it. This does the same swap from outside: it
 * defines RTPSParticipantImpl::enable() itself, and the venv's rclpy import hook loads it with
 * RTLD_GLOBAL before any participant exists, so the library's own calls (through its PLT) reach
 * this one. It registers the receivers, then enables the builtin protocols.
 *
 * It reads two members of RTPSParticipantImpl by offset, so it acts only on the build whose
 * RTPSParticipantImpl::enable() has exactly the machine code below, where those offsets were read.
 * Any other build (another Fast DDS, another compiler) gets its own enable(), untouched, and
 * owl_fastdds_enable_order() says so; tests/test_fastdds_enable_order.py fails then.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <link.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PARTICIPANT_ENABLE "_ZN8eprosima8fastrtps4rtps19RTPSParticipantImpl6enableEv"
#define BUILTIN_ENABLE "_ZN8eprosima8fastrtps4rtps16BuiltinProtocols6enableEv"
#define REGISTER_RECEIVER \
    "_ZN8eprosima8fastrtps4rtps16ReceiverResource16RegisterReceiverEPNS1_15MessageReceiverE"

/* The pinned build's RTPSParticipantImpl::enable(): mp_builtinProtocols->enable(), then
 * RegisterReceiver for each entry of the std::list m_receiverResourcelist. */
static const unsigned char PINNED_ENABLE[] = {
    0x55, 0x48, 0x89, 0xfd, 0x53, 0x48, 0x81, 0xc5, 0xc8, 0x07, 0x00, 0x00, 0x48, 0x83, 0xec, 0x08,
    0x48, 0x8b, 0xbf, 0xa0, 0x06, 0x00, 0x00, 0xe8, 0x04, 0xe8, 0xe3, 0xff, 0x48, 0x8b, 0x5d, 0x00,
    0x48, 0x39, 0xdd, 0x74, 0x20, 0x66, 0x66, 0x2e, 0x0f, 0x1f, 0x84, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x48, 0x8b, 0x73, 0x20, 0x48, 0x8b, 0x7b, 0x10, 0xe8, 0xb3, 0xa8, 0xe3, 0xff, 0x48, 0x8b, 0x1b,
    0x48, 0x39, 0xdd, 0x75, 0xeb, 0x48, 0x83, 0xc4, 0x08, 0x5b, 0x5d, 0xc3,
};
/* The offsets in that code. */
enum {
    BUILTIN_PROTOCOLS_AT = 0x6a0, /* BuiltinProtocols* in RTPSParticipantImpl */
    RECEIVER_LIST_AT = 0x7c8,     /* the list's sentinel node in RTPSParticipantImpl */
    NODE_RESOURCE_AT = 0x10,      /* ReceiverResource* in a list node */
    NODE_RECEIVER_AT = 0x20,      /* MessageReceiver* in a list node */
};

enum { NOT_CALLED = 0, RECEIVERS_FIRST = 1, UPSTREAM_ORDER = 2 };

typedef void (*member_fn)(void *self);
typedef void (*register_fn)(void *resource, void *receiver);

static member_fn upstream_enable;
static member_fn builtin_enable;
static register_fn register_receiver;
static int order = NOT_CALLED;
static pthread_once_t looked_up = PTHREAD_ONCE_INIT;

void participant_enable(void *participant) __asm__(PARTICIPANT_ENABLE);

enum { MAX_OBJECTS = 512 };
struct loaded_objects {
    const char *names[MAX_OBJECTS];
    size_t count;
};

static int collect_name(struct dl_phdr_info *info, size_t size, void *data)
{
    struct loaded_objects *objects = data;
    (void)size;
    if (info->dlpi_name != NULL && info->dlpi_name[0] != '\0' && objects->count < MAX_OBJECTS) {
        objects->names[objects->count++] = info->dlpi_name;
    }
    return 0;
}

/* The library whose enable() this one stands in for: the loaded object that defines it too. */
static void *library_defining_enable(void)
{
    /* Collected first: dlopen inside dl_iterate_phdr's callback would take the loader's lock
     * that the iteration holds. */
    static struct loaded_objects objects;
    dl_iterate_phdr(collect_name, &objects);
    for (size_t i = 0; i < objects.count; ++i) {
        void *handle = dlopen(objects.names[i], RTLD_LAZY | RTLD_NOLOAD);
        if (handle == NULL) {
            continue;
        }
        void *enable = dlsym(handle, PARTICIPANT_ENABLE);
        if (enable != NULL && enable != (void *)participant_enable) {
            return handle; /* kept open: the library stays loaded while its participants live */
        }
        dlclose(handle);
    }
    return NULL;
}

static void look_up(void)
{
    void *library = library_defining_enable();
    if (library == NULL) {
        fprintf(stderr, "owl_fastdds_enable_order: no Fast DDS library defines %s\n", PARTICIPANT_ENABLE);
        abort();
    }
    upstream_enable = (member_fn)dlsym(library, PARTICIPANT_ENABLE);
    builtin_enable = (member_fn)dlsym(library, BUILTIN_ENABLE);
    register_receiver = (register_fn)dlsym(library, REGISTER_RECEIVER);
    int pinned = memcmp((const void *)upstream_enable, PINNED_ENABLE, sizeof PINNED_ENABLE) == 0;
    int chosen = (pinned && builtin_enable != NULL && register_receiver != NULL) ? RECEIVERS_FIRST
                                                                                 : UPSTREAM_ORDER;
    __atomic_store_n(&order, chosen, __ATOMIC_RELEASE);
}

void participant_enable(void *participant)
{
    pthread_once(&looked_up, look_up);
    if (order != RECEIVERS_FIRST) {
        upstream_enable(participant);
        return;
    }
    char *self = participant;
    char *sentinel = self + RECEIVER_LIST_AT;
    for (char *node = *(char **)sentinel; node != sentinel; node = *(char **)node) {
        register_receiver(*(void **)(node + NODE_RESOURCE_AT), *(void **)(node + NODE_RECEIVER_AT));
    }
    builtin_enable(*(void **)(self + BUILTIN_PROTOCOLS_AT));
}

/* NOT_CALLED before the process's first participant, then RECEIVERS_FIRST or UPSTREAM_ORDER. */
int owl_fastdds_enable_order(void)
{
    return __atomic_load_n(&order, __ATOMIC_ACQUIRE);
}
