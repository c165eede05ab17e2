from setuptools import find_packages, setup

package_name = 'owl_windows'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=False,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description=('The windows folder: where programs without a display write their windows and read '
                 'the keys pressed on them (the venv hook, turtlesim, owl windows).'),
    license='Apache-2.0',
    tests_require=['pytest'],
)
