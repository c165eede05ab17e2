# A keyboard loop shaped like section 4.4.1's (events first, then the held keys), which presses its
# own key through the seam's keys file right between the two, where a key could land by chance.
import os
import sys

import pygame

pygame.init()
pygame.display.set_mode((200, 80))
keys_file = os.path.join(os.environ['OWL_WINDOWS_DIR'], f'pygame_key_order-{os.getpid()}', 'keys')
seen_down = False
for loop in range(200):
    for event in pygame.event.get():
        if event.type == pygame.KEYDOWN and event.key == pygame.K_LEFT:
            seen_down = True
    if loop == 5:
        with open(keys_file, 'a') as keys:
            keys.write('down left\n')
    if pygame.key.get_pressed()[pygame.K_LEFT] and not seen_down:
        print('held before its KEYDOWN', flush=True)
        sys.exit(1)
    if seen_down and pygame.key.get_pressed()[pygame.K_LEFT]:
        print(f'KEYDOWN, then held, at loop {loop}', flush=True)
        sys.exit(0)
    pygame.time.wait(10)
print('never held', flush=True)
sys.exit(2)
